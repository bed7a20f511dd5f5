// The dynamics set's model made from a body plan, the state of the bodies that persist
// carried over from the model before it by their ids.

#include "interpreters/dynamics/dynamics_set.h"

#include <algorithm>
#include <string>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/limits.h"
#include "interpreters/dynamics/mujoco_model.h"

namespace ontogen {

namespace {

// The free joint of a MuJoCo body, or -1.
int freeJointOf(const mjModel* m, int body) {
  const int first = m->body_jntadr[body];
  return first >= 0 && m->body_jntnum[body] > 0 && m->jnt_type[first] == mjJNT_FREE ? first : -1;
}

}  // namespace

struct DynamicsSet::Carried {
  JointKind kind = JointKind::Weld;
  std::array<mjtNum, 3> angle{}, speed{};  // of its hinges
  bool free = false;                       // it had the free joint, whose state follows
  std::array<mjtNum, 7> freePosition{};
  std::array<mjtNum, 6> freeVelocity{};
  bool posed = false;                      // where it was, and its speeds as a free joint's
  std::array<mjtNum, 3> position{};
  std::array<mjtNum, 4> quaternion{};
  std::array<mjtNum, 6> freeVelocityFromPose{};
};

void DynamicsSet::placeFreeBodies(const std::unordered_map<uint64_t, Carried>& carried) {
  const mjModel* m = sim_->model();
  mjData* d = sim_->data();
  bool kinematics = false;
  for (std::size_t b = 0; b < plan_.bodies.size(); ++b) {
    const int body = bodyIds_[b];
    const int free = body >= 0 ? freeJointOf(m, body) : -1;
    if (free < 0) continue;
    mjtNum* position = d->qpos + m->jnt_qposadr[free];
    mjtNum* velocity = d->qvel + m->jnt_dofadr[free];
    const auto found = carried.find(plan_.bodies[b].id);
    if (found != carried.end() && found->second.free) {
      // The same body had the free joint: its state as it was, to the bit.
      std::copy_n(found->second.freePosition.begin(), 7, position);
      std::copy_n(found->second.freeVelocity.begin(), 6, velocity);
      continue;
    }
    if (found != carried.end() && found->second.posed) {
      std::copy_n(found->second.position.begin(), 3, position);
      std::copy_n(found->second.quaternion.begin(), 4, position + 3);
      std::copy_n(found->second.freeVelocityFromPose.begin(), 6, velocity);
      continue;
    }
    // A new body at the centre: the tree placed so that the first body of it that
    // persists stands where it was, moving with that body's speeds as one rigid whole.
    if (!kinematics) {
      mj_kinematics(m, d);
      kinematics = true;
    }
    for (std::size_t k = 0; k < plan_.bodies.size(); ++k) {
      const int other = bodyIds_[k];
      const auto kept = carried.find(plan_.bodies[k].id);
      if (other < 0 || kept == carried.end() || !kept->second.posed || m->body_rootid[other] != body) continue;
      const glm::dmat3 now = frameOf(d, other);
      const glm::dvec3 nowAt = positionOf(d, other);
      mjtNum matrix[9];
      mju_quat2Mat(matrix, kept->second.quaternion.data());
      const glm::dmat3 then(glm::dvec3(matrix[0], matrix[3], matrix[6]), glm::dvec3(matrix[1], matrix[4], matrix[7]),
                            glm::dvec3(matrix[2], matrix[5], matrix[8]));
      const glm::dvec3 thenAt(kept->second.position[0], kept->second.position[1], kept->second.position[2]);
      const glm::dmat3 turn = then * glm::transpose(now);
      const glm::dvec3 at = thenAt + turn * (positionOf(d, body) - nowAt);
      const glm::dmat3 frame = turn * frameOf(d, body);
      mjtNum rows[9];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rows[3 * r + c] = frame[c][r];
      for (int i = 0; i < 3; ++i) position[i] = at[i];
      mju_mat2Quat(position + 3, rows);
      // The kept body's turning (its own frame's, into the world's) and its origin's speed.
      const auto& v = kept->second.freeVelocityFromPose;
      const glm::dvec3 spin = then * glm::dvec3(v[3], v[4], v[5]);
      const glm::dvec3 linear = glm::dvec3(v[0], v[1], v[2]) + glm::cross(spin, at - thenAt);
      const glm::dvec3 own = glm::transpose(frame) * spin;
      for (int i = 0; i < 3; ++i) {
        velocity[i] = linear[i];
        velocity[3 + i] = own[i];
      }
      break;
    }
  }
}

void DynamicsSet::build(const BodyPlan& plan, double time) {
  if (const int depth = nestingDepth(plan); depth > kDeepestBodies)
    throw LimitError("the dynamics set's body has " + std::to_string(depth) +
                     " parts hanging one from another, and MuJoCo reads at most " + std::to_string(kDeepestBodies) +
                     ": fewer segments a rod (elastic(n)), fewer rods on a path, or a shorter creature");
  // The bodies that persist keep their hinges' angles and speeds, found by their ids, and
  // where they are and how they move in the world (for a free joint that moved to another
  // body as the centre of the body moved).
  auto carriedPose = [](const mjModel* m, const mjData* d, int body, Carried& state) {
    if (const int free = freeJointOf(m, body); free >= 0) {
      state.free = true;
      std::copy_n(d->qpos + m->jnt_qposadr[free], 7, state.freePosition.begin());
      std::copy_n(d->qvel + m->jnt_dofadr[free], 6, state.freeVelocity.begin());
    }
    state.posed = true;
    std::copy_n(d->xpos + 3 * body, 3, state.position.begin());
    std::copy_n(d->xquat + 4 * body, 4, state.quaternion.begin());
    // A free joint's speeds: its origin's in the world, its turning in its own frame.
    mjtNum world[6], local[6];
    mj_objectVelocity(m, d, mjOBJ_XBODY, body, world, 0);
    mj_objectVelocity(m, d, mjOBJ_XBODY, body, local, 1);
    std::copy_n(world + 3, 3, state.freeVelocityFromPose.begin());
    std::copy_n(local, 3, state.freeVelocityFromPose.begin() + 3);
  };
  std::unordered_map<uint64_t, Carried> carried;
  if (sim_) {
    const mjModel* m = sim_->model();
    mjData* d = sim_->data();
    // A step leaves the kinematics of the positions before it.
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_comVel(m, d);
    for (std::size_t b = 0; b < plan_.bodies.size(); ++b) {
      const int body = bodyIds_[b];
      if (body < 0) continue;
      Carried state;
      state.kind = plan_.bodies[b].kind;
      carriedPose(m, d, body, state);
      carried.emplace(plan_.bodies[b].id, state);
    }
    for (const Hinge& hinge : hinges_) {
      Carried& state = carried[plan_.bodies[static_cast<std::size_t>(hinge.body)].id];
      state.angle[static_cast<std::size_t>(hinge.dof)] = d->qpos[hinge.qpos];
      state.speed[static_cast<std::size_t>(hinge.dof)] = d->qvel[hinge.dof_address];
    }
  }
  plan_ = plan;
  // The room only grows over a run: a model rebuilt as the body grows keeps what the
  // steps before needed.
  const MujocoRoom usual = usualRoom(plan_);
  room_ = {std::max(room_.contacts, usual.contacts), std::max(room_.rows, usual.rows)};
  checkRoomMemory(room_, "the dynamics set's body of " + std::to_string(plan_.bodies.size()) + " parts needs");
  mjcf_ = mjcfOf(plan_, physics_, target_.stem.empty() ? "dynamics" : target_.stem, room_);
  sim_ = std::make_unique<MujocoModel>(mjcf_);
  knotsStale_ = true;
  const mjModel* m = sim_->model();
  mjData* d = sim_->data();
  start_ = time;
  steps_ = 0;
  ++stats_.rebuilds;
  stats_.simulating = true;
  groundGeom_ = mj_name2id(m, mjOBJ_GEOM, "ground");
  bodyIds_.assign(plan_.bodies.size(), -1);
  planOfBody_.assign(static_cast<std::size_t>(m->nbody), -1);
  hinges_.clear();
  for (std::size_t b = 0; b < plan_.bodies.size(); ++b) {
    const PlanBody& body = plan_.bodies[b];
    const int index = static_cast<int>(b);
    bodyIds_[b] = mj_name2id(m, mjOBJ_BODY, bodyName(index).c_str());
    if (bodyIds_[b] >= 0) planOfBody_[static_cast<std::size_t>(bodyIds_[b])] = index;
    // The hinges start at the kinematic angles (the free roots where the plan has them).
    const std::array<double, 3> angles = hingeAngles(body.kind, body.base, body.orientation);
    for (int dof = 0; dof < hingeCount(body.kind); ++dof) {
      Hinge hinge;
      hinge.body = index;
      hinge.dof = dof;
      const int joint = mj_name2id(m, mjOBJ_JOINT, hingeName(index, dof).c_str());
      hinge.qpos = m->jnt_qposadr[joint];
      hinge.dof_address = m->jnt_dofadr[joint];
      hinge.actuator = mj_name2id(m, mjOBJ_ACTUATOR, ("s" + std::to_string(index) + "_" + std::to_string(dof)).c_str());
      const HingeRange& range = body.ranges[static_cast<std::size_t>(dof)];
      hinge.range = {range.set, range.lo, range.hi};
      d->qpos[hinge.qpos] = angles[static_cast<std::size_t>(dof)];
      hinges_.push_back(hinge);
    }
  }
  // Carried over where a body of the same id and kind persists.
  for (std::size_t b = 0; b < plan_.bodies.size(); ++b) {
    const auto found = carried.find(plan_.bodies[b].id);
    if (bodyIds_[b] >= 0 && found != carried.end() && found->second.kind == plan_.bodies[b].kind) ++stats_.carried;
  }
  for (const Hinge& hinge : hinges_) {
    const PlanBody& body = plan_.bodies[static_cast<std::size_t>(hinge.body)];
    const auto found = carried.find(body.id);
    if (found == carried.end() || found->second.kind != body.kind) continue;
    d->qpos[hinge.qpos] = found->second.angle[static_cast<std::size_t>(hinge.dof)];
    d->qvel[hinge.dof_address] = found->second.speed[static_cast<std::size_t>(hinge.dof)];
  }
  if (!carried.empty()) placeFreeBodies(carried);
  drags_.clear();
  for (std::size_t b = skeletonBodies_; b < plan_.bodies.size(); ++b) {
    const PlanBody& body = plan_.bodies[b];
    if (body.kind == JointKind::Weld || bodyIds_[b] < 0 || body.limbs.empty()) continue;
    const PlanLimb& own = body.limbs.front();
    drags_.push_back({bodyIds_[b], own.radius, glm::length(own.end - own.start)});
  }
  // Each rod's tip: on the last body of its own, or on what it is welded to.
  rodTipsAtRest_.clear();
  for (const RodSpec& rod : rods_) {
    const glm::dvec3 tip = rod.base + rod.length * rod.frame[0];
    int holder = -1;
    for (std::size_t b = 0; b < plan_.bodies.size(); ++b)
      for (const PlanLimb& limb : plan_.bodies[b].limbs)
        if (limb.cylinder && glm::length(limb.end - tip) < 1e-12 * std::max(1.0, rod.length)) holder = static_cast<int>(b);
    rodTipsAtRest_.push_back({holder, tip});
  }
  setControls(time);
  mj_forward(m, d);
}

}  // namespace ontogen
