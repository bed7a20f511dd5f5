// The dynamics set's plants: the rods a word drew as chains of bodies joined by springs,
// and the wind's drag on them.

#include "interpreters/dynamics/dynamics_set.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "interpreters/dynamics/mujoco_model.h"

namespace ontogen {

void DynamicsSet::addRods(BodyPlan& plan, const std::vector<RodSpec>& rods) const {
  std::vector<int> tipBody(rods.size(), -1);
  for (std::size_t k = 0; k < rods.size(); ++k) {
    const RodSpec& rod = rods[k];
    int parent = rod.parent >= 0 ? tipBody[static_cast<std::size_t>(rod.parent)] : -1;
    // A first rod drawn on a creature's body hangs from the joint's body (the skeleton's
    // bodies come first in the plan, in its joints' order).
    if (parent < 0 && rod.joint >= 0 && static_cast<std::size_t>(rod.joint) < plan.bodies.size()) parent = rod.joint;
    if (parent < 0) {
      // A root rod is clamped at its base: a body fixed in the world.
      PlanBody anchor;
      anchor.id = rod.id ^ 0xA5A5A5A5A5A5A5A5ull;
      anchor.kind = JointKind::Weld;
      anchor.position = rod.base;
      anchor.base = anchor.orientation = rod.frame;
      parent = static_cast<int>(plan.bodies.size());
      plan.bodies.push_back(anchor);
    }
    const glm::dvec3 along = rod.frame[0];
    const glm::dvec3 tip = rod.base + rod.length * along;
    auto limb = [&](const glm::dvec3& a, const glm::dvec3& b) {
      return PlanLimb{a, b, rod.radius, rod.density, true, false};
    };
    std::vector<PlanLimb>& held = plan.bodies[static_cast<std::size_t>(parent)].limbs;
    if (rod.stiffness <= 0) {
      held.push_back(limb(rod.base, tip));
      tipBody[k] = parent;
      continue;
    }
    // As the elastic design model cuts it: n segments of h, a spring of EI / h at each
    // segment's middle; the half segment at the base moves with what the rod hangs from.
    const int n = rod.segments;
    const double h = rod.length / n;
    held.push_back(limb(rod.base, rod.base + h / 2 * along));
    int previous = parent;
    for (int i = 0; i < n; ++i) {
      PlanBody body;
      body.id = rod.id * 131 + static_cast<uint64_t>(i) + 1;
      body.parent = previous;
      body.kind = JointKind::Bend;
      body.position = rod.base + (h / 2 + i * h) * along;
      body.base = body.orientation = rod.frame;
      body.limbs.push_back(limb(body.position, i + 1 == n ? tip : body.position + h * along));
      body.spring = rod.stiffness / h;
      body.damping = wordDamping_ * body.spring;
      body.driven = false;
      previous = static_cast<int>(plan.bodies.size());
      plan.bodies.push_back(std::move(body));
    }
    tipBody[k] = previous;
  }
}


void DynamicsSet::applyWind(double time) {
  if (drags_.empty()) return;
  const mjModel* m = sim_->model();
  mjData* d = sim_->data();
  const glm::dvec3 air = wind_.speed * (1 + wind_.gust * std::sin(2 * std::numbers::pi * time / wind_.period));
  for (const Drag& drag : drags_) {
    mjtNum* force = d->xfrc_applied + 6 * drag.body;
    mjtNum velocity[6];
    mj_objectVelocity(m, d, mjOBJ_BODY, drag.body, velocity, 0);
    // The air across the segment, relative to its centre's motion.
    const glm::dvec3 relative = air - glm::dvec3(velocity[3], velocity[4], velocity[5]);
    const glm::dvec3 axis = frameOf(d, drag.body)[0];
    const glm::dvec3 across = relative - glm::dot(relative, axis) * axis;
    const glm::dvec3 pull =
        0.5 * kAirDensity * kDragCoefficient * 2 * drag.radius * drag.length * glm::length(across) * across;
    for (int k = 0; k < 3; ++k) {
      force[k] = pull[k];
      force[3 + k] = 0;
    }
  }
}

}  // namespace ontogen
