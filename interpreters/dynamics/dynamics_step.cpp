// The dynamics set's simulation stepping at its own fixed step: the room for contacts grown
// when a step runs out, the measures summed over the steps, the state read at a frame's time.

#include "interpreters/dynamics/dynamics_set.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/limits.h"
#include "interpreters/dynamics/mujoco_model.h"

namespace ontogen {

namespace {

// What a step reads from the data besides the model: saved before a step, it lets the
// step be taken again in another model of the same bodies.
struct StepInputs {
  std::vector<mjtNum> values;

  // The arrays, in one order for saving and restoring.
  template <typename Visit>
  static void each(const mjModel* m, mjData* d, Visit visit) {
    visit(&d->time, 1);
    visit(d->qpos, m->nq);
    visit(d->qvel, m->nv);
    visit(d->act, m->na);
    visit(d->ctrl, m->nu);
    visit(d->qacc_warmstart, m->nv);
    visit(d->qfrc_applied, m->nv);
    visit(d->xfrc_applied, 6 * m->nbody);
    visit(d->mocap_pos, 3 * m->nmocap);
    visit(d->mocap_quat, 4 * m->nmocap);
  }
  void save(const mjModel* m, mjData* d) {
    values.clear();
    each(m, d, [&](mjtNum* array, int n) { values.insert(values.end(), array, array + n); });
  }
  void restore(const mjModel* m, mjData* d) const {
    std::size_t at = 0;
    each(m, d, [&](mjtNum* array, int n) {
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(at), n, array);
      at += static_cast<std::size_t>(n);
    });
  }
};

}  // namespace

void DynamicsSet::stepWithRoom() {
  // MuJoCo drops the contacts and constraints it has no room for (and warns): the step is
  // taken again, from the same inputs, in the same model with twice the room.
  thread_local StepInputs inputs;
  inputs.save(sim_->model(), sim_->data());
  sim_->step();
  while (sim_->lastStepOutOfRoom()) {
    const MujocoRoom more = doubled(room_, mostRoom(plan_));
    if (more.contacts == room_.contacts && more.rows == room_.rows) {
      crowded_.add(1, site_);
      return;
    }
    std::ostringstream why;
    why << "at t = " << stepTime(steps_ + 1) << " s the dynamics set's body touched the ground at more than "
        << room_.contacts << " points";
    if (stats_.instabilities > 0 || sim_->lastStepReset())
      why << " while its simulation was unstable (MuJoCo reset it; a smaller #timestep or gentler servos may steady it)";
    why << ", and needs";
    checkRoomMemory(more, why.str());
    room_ = more;
    mjcf_ = mjcfOf(plan_, physics_, target_.stem.empty() ? "dynamics" : target_.stem, room_);
    if (!firstMjcf_.empty()) {
      // The written model keeps its keyframe; it gets the room the run needed.
      const std::size_t from = firstMjcf_.find("<size "), to = firstMjcf_.find("/>", from);
      if (from != std::string::npos && to != std::string::npos) firstMjcf_.replace(from, to + 2 - from, sizeElement(room_));
    }
    auto roomier = std::make_unique<MujocoModel>(mjcf_);
    inputs.restore(roomier->model(), roomier->data());
    sim_ = std::move(roomier);
    ++stats_.roomGrowths;
    sim_->step();
  }
}

void DynamicsSet::checkRoomMemory(MujocoRoom room, const std::string& why) const {
  const uint64_t bytes = mujocoRoomBytes(room), limit = def_.maxMemoryBytes;
  if (limit == 0 || bytes <= limit) return;
  auto mebibytes = [](uint64_t n) { return std::to_string((n + (1u << 20) - 1) >> 20); };
  throw LimitError(why + " MuJoCo's room for " + std::to_string(room.contacts) + " contacts and " +
                   std::to_string(room.rows) + " constraint rows, about " + mebibytes(bytes) +
                   " MiB, past the memory limit of " + mebibytes(limit) +
                   " MiB; raise it with --max-memory MIB, or keep fewer limbs on the ground");
}

void DynamicsSet::advanceTo(double time) {
  if (!sim_) return;
  const mjModel* m = sim_->model();
  mjData* d = sim_->data();
  const double h = physics_.timestep;
  while (stepTime(steps_ + 1) <= time + 1e-9 * std::max(1.0, std::abs(time))) {
    setControls(stepTime(steps_));
    applyWind(stepTime(steps_));
    stepWithRoom();
    d = sim_->data();
    m = sim_->model();
    ++steps_;
    stats_.simulatedTime += h;
    if (sim_->lastStepReset()) {
      unstable_.add(1, site_);
      ++stats_.instabilities;
    }
    // The servos' work and the ground contacts' sliding over the step.
    for (const Hinge& hinge : hinges_)
      if (hinge.actuator >= 0)
        stats_.energy += std::abs(d->actuator_force[hinge.actuator] * d->qvel[hinge.dof_address]) * h;
    for (int c = 0; c < d->ncon; ++c) {
      const mjContact& contact = d->contact[c];
      if (contact.geom1 != groundGeom_ && contact.geom2 != groundGeom_) continue;
      const int body = m->geom_bodyid[contact.geom1 == groundGeom_ ? contact.geom2 : contact.geom1];
      mjtNum velocity[6];
      mj_objectVelocity(m, d, mjOBJ_BODY, body, velocity, 0);
      const glm::dvec3 w(velocity[0], velocity[1], velocity[2]), v(velocity[3], velocity[4], velocity[5]);
      const glm::dvec3 at = glm::dvec3(contact.pos[0], contact.pos[1], contact.pos[2]) - positionOf(d, body);
      const glm::dvec3 point = v + glm::cross(w, at);
      stats_.slip += std::hypot(point.x, point.z) * h;
    }
  }
}

void DynamicsSet::stateAt(double time) {
  const mjModel* m = sim_->model();
  mjData* s = sim_->scratch();
  mj_copyData(s, m, sim_->data());
  const double now = stepTime(steps_);
  if (time > now + 1e-12) {
    // A partial step to the frame's time, on a copy: the simulation keeps its own steps.
    setControls(now);
    mju_copy(s->ctrl, sim_->data()->ctrl, m->nu);
    mjModel* model = sim_->model();
    const double h = model->opt.timestep;
    model->opt.timestep = time - now;
    mj_step(model, s);
    model->opt.timestep = h;
  }
  mj_forward(m, s);
}

}  // namespace ontogen
