// The dynamics set's servos: their targets, the kinematic pose of the word replayed on the
// control grid and followed linearly between its knots.

#include "interpreters/dynamics/dynamics_set.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "interpreters/dynamics/mujoco_model.h"

namespace ontogen {

bool DynamicsSet::poseTargets(double time, std::vector<double>& out) {
  replay(tape_, FrameTarget{{}, {}, 0, 1, time}, replay_, stepStarts_);
  const auto& joints = replay_.scene().skeleton.joints;
  if (joints.size() != skeletonBodies_ || stepStarts_.size() != joints.size()) return false;
  out.clear();
  std::size_t body = plan_.bodies.size();
  std::array<double, 3> angles{};
  for (const Hinge& hinge : hinges_) {
    if (hinge.actuator < 0) continue;
    if (static_cast<std::size_t>(hinge.body) != body) {
      body = static_cast<std::size_t>(hinge.body);
      angles = hingeAngles(plan_.bodies[body].kind, stepStarts_[body].base, joints[body].orientation);
    }
    double target = angles[static_cast<std::size_t>(hinge.dof)];
    if (hinge.range.set) target = std::clamp(target, hinge.range.lo, hinge.range.hi);
    out.push_back(target);
  }
  return true;
}

void DynamicsSet::setControls(double time) {
  // A tape that no longer makes the model's joints holds the controls as they are.
  mjData* d = sim_->data();
  if (!(control_ > 0)) {
    if (!poseTargets(time, atKnot_.targets)) return;
    std::size_t i = 0;
    for (const Hinge& hinge : hinges_)
      if (hinge.actuator >= 0) d->ctrl[hinge.actuator] = atKnot_.targets[i++];
    return;
  }
  // The pose is taken on a grid of knots from time 0, whatever the frames; the replay of
  // the word, not MuJoCo, is then most of a step's cost when taken at every step.
  const auto knot = static_cast<long>(std::floor(time / control_ + 1e-9));
  if (knotsStale_ || knot != knot_) {
    if (!knotsStale_ && knot == knot_ + 1) {
      std::swap(atKnot_, atNextKnot_);
    } else {
      atKnot_.valid = poseTargets(static_cast<double>(knot) * control_, atKnot_.targets);
    }
    atNextKnot_.valid = poseTargets(static_cast<double>(knot + 1) * control_, atNextKnot_.targets);
    knot_ = knot;
    knotsStale_ = false;
    // The way from each target to the next, the short way round (a hinge's angle is read
    // in (-pi, pi]): once a knot, not at each step.
    if (atKnot_.valid && atNextKnot_.valid) {
      towardsNextKnot_.resize(atKnot_.targets.size());
      for (std::size_t i = 0; i < towardsNextKnot_.size(); ++i)
        towardsNextKnot_[i] = std::remainder(atNextKnot_.targets[i] - atKnot_.targets[i], 2 * std::numbers::pi);
    }
  }
  if (!atKnot_.valid || !atNextKnot_.valid) return;
  const double along = std::clamp((time - static_cast<double>(knot) * control_) / control_, 0.0, 1.0);
  std::size_t i = 0;
  for (const Hinge& hinge : hinges_) {
    if (hinge.actuator < 0) continue;
    double target = atKnot_.targets[i] + towardsNextKnot_[i] * along;
    ++i;
    if (hinge.range.set) target = std::clamp(target, hinge.range.lo, hinge.range.hi);
    d->ctrl[hinge.actuator] = target;
  }
}


std::vector<ServoTarget> DynamicsSet::targets() const {
  std::vector<ServoTarget> out;
  if (!sim_) return out;
  for (const Hinge& hinge : hinges_)
    if (hinge.actuator >= 0) out.push_back({hinge.body, hinge.dof, sim_->data()->ctrl[hinge.actuator]});
  return out;
}

}  // namespace ontogen
