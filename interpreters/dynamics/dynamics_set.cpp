#include "interpreters/dynamics/dynamics_set.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/limits.h"
#include "interpreters/creature/creature_commands.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/dynamics/mujoco_model.h"
#include "interpreters/formats/scene_output.h"
#include "interpreters/output_file.h"

namespace ontogen {

namespace {

bool finite(std::span<const double> args) {
  return std::all_of(args.begin(), args.end(), [](double v) { return std::isfinite(v); });
}

// The joint a creature command makes, if it makes one.
std::optional<JointKind> jointKindOf(CreatureOp op) {
  switch (op) {
    case CreatureOp::Gait: return JointKind::Free;
    case CreatureOp::Bend: return JointKind::Bend;
    case CreatureOp::Hinge: return JointKind::Hinge;
    case CreatureOp::Hip: return JointKind::Hip;
    case CreatureOp::Knee: return JointKind::Knee;
    case CreatureOp::Foot: return JointKind::Weld;
    default: return std::nullopt;
  }
}

CreatureSetDef creatureDefOf(const DynamicsSetDef& def, LimbMeshing meshing) {
  CreatureSetDef inner;
  inner.radians = def.radians;
  inner.ground = def.physics.ground;
  inner.meshing = meshing;
  return inner;
}


// World frame (columns H, L, U) of a MuJoCo body: its xmat, row-major.
glm::dmat3 frameOf(const mjData* d, int body) {
  const mjtNum* x = d->xmat + 9 * body;
  return glm::dmat3(glm::dvec3(x[0], x[3], x[6]), glm::dvec3(x[1], x[4], x[7]), glm::dvec3(x[2], x[5], x[8]));
}

glm::dvec3 positionOf(const mjData* d, int body) {
  const mjtNum* x = d->xpos + 3 * body;
  return {x[0], x[1], x[2]};
}

std::string numbers(const mjtNum* values, int count) {
  std::string out;
  char text[32];
  for (int i = 0; i < count; ++i) {
    std::snprintf(text, sizeof text, "%s%.17g", i > 0 ? " " : "", values[i]);
    out += text;
  }
  return out;
}

}  // namespace

DynamicsSet::DynamicsSet(const DynamicsSetDef& def)
    : def_(def),
      inner_(creatureDefOf(def, LimbMeshing::GrownFrames)),
      replay_(creatureDefOf(def, LimbMeshing::GrownFrames)),
      draw_(creatureDefOf(def, def.meshing)),
      physics_(def.physics),
      wordPhysics_(def.physics),
      scene_{0, Geometry(MeshDef{}), {}, {}} {
  if (const char* error = physicsError(def.physics)) throw std::invalid_argument(error);
}

DynamicsSet::~DynamicsSet() = default;

bool DynamicsSet::knows(std::string_view command) const {
  return findDynamicsCommand(command) != nullptr || findCreatureCommand(command) != nullptr;
}

void DynamicsSet::beginFrame(const FrameTarget& target) {
  target_ = target;
  framed_ = true;
}

void DynamicsSet::beginWord(double time) {
  wordTime_ = time;
  wordTape_.clear();
  wordPhysics_ = def_.physics;
  wordRods_.clear();
  rodPath_ = {};
  rodStack_.clear();
  wordWind_ = {};
  wordDamping_ = kRodDamping;
  wordControl_ = kControlPeriod;
  starts_.clear();
  inner_.beginFrame(FrameTarget{{}, {}, 0, 1, time});
  inner_.beginWord(time);
}

void DynamicsSet::beginCell(const CellContext& cell) {
  inner_.beginCell(cell);
  cellId_ = cell.id;
  rodsInCell_ = 0;
  TapeEntry entry;
  entry.cell = true;
  entry.context = cell;
  wordTape_.push_back(std::move(entry));
}

void DynamicsSet::execute(std::string_view command, std::span<const double> args) {
  if (const DynamicsCommand* own = findDynamicsCommand(command)) {
    executeCommand(static_cast<int>(own - dynamicsCommands().data()), command, args);
    return;
  }
  if (const CreatureCommand* creature = findCreatureCommand(command))
    executeCommand(static_cast<int>(dynamicsCommands().size() + (creature - creatureCommands().data())), command, args);
}

void DynamicsSet::executeCommand(int id, std::string_view command, std::span<const double> args) {
  const auto own = dynamicsCommands();
  if (id < 0 || static_cast<std::size_t>(id) >= own.size() + creatureCommands().size()) {
    execute(command, args);
    return;
  }
  if (static_cast<std::size_t>(id) < own.size()) {
    const DynamicsCommand& found = own[static_cast<std::size_t>(id)];
    if (static_cast<int>(args.size()) < found.minArity || static_cast<int>(args.size()) > found.maxArity ||
        !finite(args)) {
      badArguments_.add(1, site_);
      return;
    }
    runOwn(found.op, args);
    return;
  }
  const int creature = id - static_cast<int>(own.size());
  // A branch keeps its rods' path: [ pushes the last rod and the rods' make, ] pops them.
  const CreatureOp op = creatureCommands()[static_cast<std::size_t>(creature)].op;
  if (op == CreatureOp::Push) rodStack_.push_back(rodPath_);
  if (op == CreatureOp::Pop && !rodStack_.empty()) {
    rodPath_ = rodStack_.back();
    rodStack_.pop_back();
  }
  inner_.locate(site_);
  runCreature(inner_, creature, args, starts_);
  TapeEntry entry;
  entry.site = site_;
  entry.command = creature;
  entry.args.assign(args.begin(), args.end());
  wordTape_.push_back(std::move(entry));
}

void DynamicsSet::runOwn(DynamicsOp op, std::span<const double> args) {
  PhysicsDef next = wordPhysics_;
  bool bad = false;
  switch (op) {
    case DynamicsOp::Density: next.density = args[0]; break;
    case DynamicsOp::Friction: next.friction = args[0]; break;
    case DynamicsOp::Gravity: next.gravity = args[0]; break;
    case DynamicsOp::Servo:
      next.kp = args[0];
      next.kd = args[1];
      if (args.size() > 2) next.torque = args[2];
      break;
    case DynamicsOp::Stiffness:
      bad = !(args[0] >= 0);
      if (!bad) rodPath_.stiffness = args[0];
      break;
    case DynamicsOp::Elastic:
      bad = !(args[0] >= 1 && args[0] <= 64);
      if (!bad) rodPath_.segments = static_cast<int>(std::lround(args[0]));
      break;
    case DynamicsOp::Damping:
      bad = !(args[0] >= 0);
      if (!bad) wordDamping_ = args[0];
      break;
    case DynamicsOp::Wind: {
      Air air;
      air.speed = {args[0], args[1], args[2]};
      if (args.size() > 3) air.gust = args[3];
      if (args.size() > 4) air.period = args[4];
      bad = !(air.period > 0);
      if (!bad) wordWind_ = air;
      break;
    }
    case DynamicsOp::Control:
      bad = !(args[0] >= 0 && args[0] <= 1);
      if (!bad) wordControl_ = args[0];
      break;
    case DynamicsOp::Rod: {
      RodSpec rod;
      rod.length = args[0];
      rod.radius = args[1];
      rod.density = args.size() > 2 ? args[2] : wordPhysics_.density;
      if (!(rod.length > 0) || !(rod.radius > 0) || !(rod.density > 0)) {
        bad = true;
        break;
      }
      // The cell's id and the rod's place among its rods: stable while the cell lives.
      rod.id = cellId_ * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(++rodsInCell_);
      rod.parent = rodPath_.rod;
      rod.joint = inner_.turtleJoint();
      rod.base = inner_.turtlePosition();
      rod.frame = inner_.turtleFrame();
      rod.stiffness = rodPath_.stiffness;
      rod.segments = rodPath_.segments;
      rodPath_.rod = static_cast<int>(wordRods_.size());
      wordRods_.push_back(rod);
      // The turtle moves to the rod's tip, in the word and in every replay of it.
      const CreatureCommand* move = findCreatureCommand("f");
      const int index = static_cast<int>(move - creatureCommands().data());
      const std::array<double, 1> length{rod.length};
      inner_.locate(site_);
      runCreature(inner_, index, length, starts_);
      TapeEntry entry;
      entry.site = site_;
      entry.command = index;
      entry.args.assign(length.begin(), length.end());
      wordTape_.push_back(std::move(entry));
      break;
    }
  }
  if (bad || physicsError(next) != nullptr) {
    badArguments_.add(1, site_);
    return;
  }
  wordPhysics_ = next;
}

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

void DynamicsSet::runCreature(CreatureSet& set, int command, std::span<const double> args,
                              std::vector<JointStart>& starts) {
  const CreatureCommand& row = creatureCommands()[static_cast<std::size_t>(command)];
  const std::optional<JointKind> kind = jointKindOf(row.op);
  if (!kind) {
    set.executeCommand(command, row.name, args);
    return;
  }
  const JointStart start{*kind, set.turtleFrame(), set.turtleRanges()};
  const std::size_t before = set.scene().skeleton.joints.size();
  set.executeCommand(command, row.name, args);
  if (set.scene().skeleton.joints.size() == before + 1) starts.push_back(start);
}

void DynamicsSet::replay(const std::vector<TapeEntry>& tape, const FrameTarget& target, CreatureSet& set,
                         std::vector<JointStart>& starts) {
  starts.clear();
  const double time = target.time;
  set.beginFrame(target);
  set.beginWord(time);
  for (const TapeEntry& entry : tape) {
    if (entry.cell) {
      CellContext context = entry.context;
      context.time = time;
      set.beginCell(context);
      continue;
    }
    set.locate(entry.site);
    runCreature(set, entry.command, entry.args, starts);
  }
}

BodyPlan DynamicsSet::planOf(const CreatureSet& set, const std::vector<JointStart>& starts) const {
  BodyPlan plan;
  const auto& joints = set.scene().skeleton.joints;
  if (starts.size() != joints.size()) return plan;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    PlanBody body;
    body.id = joints[i].id;
    body.parent = joints[i].parent;
    body.kind = starts[i].kind;
    body.position = joints[i].position;
    body.orientation = joints[i].orientation;
    body.base = body.kind == JointKind::Free ? body.orientation : starts[i].base;
    // A hip's third range holds its swivel about the hip-foot line, not its roll about H.
    const int ranged = body.kind == JointKind::Hip ? 2 : 3;
    for (int dof = 0; dof < ranged; ++dof) {
      const CreatureRange& range = starts[i].ranges[static_cast<std::size_t>(dof)];
      body.ranges[static_cast<std::size_t>(dof)] = {range.set, range.lo, range.hi};
    }
    plan.bodies.push_back(std::move(body));
  }
  for (const CreatureLimb& limb : set.wordLimbs()) {
    if (limb.joint < 0 || static_cast<std::size_t>(limb.joint) >= plan.bodies.size()) continue;
    plan.bodies[static_cast<std::size_t>(limb.joint)].limbs.push_back(
        {limb.start, limb.start + limb.length * limb.frame[0], (limb.r0 + limb.r1) / 2});
  }
  return plan;
}

void DynamicsSet::endWord() {
  inner_.endWord();
  // The simulation reaches this word's time on the last word's targets, then takes this one.
  advanceTo(wordTime_);
  tape_.swap(wordTape_);
  tapeTime_ = wordTime_;
  knotsStale_ = true;
  control_ = wordControl_;
  BodyPlan plan = planOf(inner_, starts_);
  const std::size_t skeleton = plan.bodies.size();
  if (skeleton == inner_.scene().skeleton.joints.size()) addRods(plan, wordRods_);
  wind_ = wordWind_;
  const bool hasHinges = std::any_of(plan.bodies.begin(), plan.bodies.end(),
                                     [](const PlanBody& b) { return b.kind != JointKind::Weld; });
  const bool physicsChanged = wordPhysics_.density != physics_.density || wordPhysics_.friction != physics_.friction ||
                              wordPhysics_.kp != physics_.kp || wordPhysics_.kd != physics_.kd ||
                              wordPhysics_.torque != physics_.torque || wordPhysics_.gravity != physics_.gravity ||
                              wordDamping_ != damping_ || wordRods_.size() != rods_.size();
  if (!hasHinges) {
    sim_.reset();
    plan_ = {};
    return;
  }
  if (!sim_ || !plan.sameStructure(plan_) || physicsChanged) {
    physics_ = wordPhysics_;
    damping_ = wordDamping_;
    rods_ = wordRods_;
    skeletonBodies_ = skeleton;
    build(plan, wordTime_);
  }
}

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
  countedInstabilities_ = 0;
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
  }
  if (!atKnot_.valid || !atNextKnot_.valid) return;
  const double along = std::clamp((time - static_cast<double>(knot) * control_) / control_, 0.0, 1.0);
  std::size_t i = 0;
  for (const Hinge& hinge : hinges_) {
    if (hinge.actuator < 0) continue;
    const double from = atKnot_.targets[i], to = atNextKnot_.targets[i];
    ++i;
    // The short way round: a hinge's angle is read in (-pi, pi].
    double target = from + std::remainder(to - from, 2 * std::numbers::pi) * along;
    if (hinge.range.set) target = std::clamp(target, hinge.range.lo, hinge.range.hi);
    d->ctrl[hinge.actuator] = target;
  }
}

namespace {

// What a step reads from the data besides the model: saved before a step, it lets the
// step be taken again in another model of the same bodies.
struct StepInputs {
  std::vector<mjtNum> values;
  mjWarningStat warnings[mjNWARNING];

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
    std::copy_n(d->warning, mjNWARNING, warnings);
  }
  void restore(const mjModel* m, mjData* d) const {
    std::size_t at = 0;
    each(m, d, [&](mjtNum* array, int n) {
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(at), n, array);
      at += static_cast<std::size_t>(n);
    });
    std::copy_n(warnings, mjNWARNING, d->warning);
  }
};

// MuJoCo's warning counts only grow over a data's life, and a model's first pose may
// already have run out (its forward at build): the step ran out when it raised them.
bool outOfRoom(const mjData* d, const StepInputs& before) {
  return d->warning[mjWARN_CONTACTFULL].number > before.warnings[mjWARN_CONTACTFULL].number ||
         d->warning[mjWARN_CNSTRFULL].number > before.warnings[mjWARN_CNSTRFULL].number;
}

}  // namespace

void DynamicsSet::stepWithRoom() {
  // MuJoCo drops the contacts and constraints it has no room for (and warns): the step is
  // taken again, from the same inputs, in the same model with twice the room.
  thread_local StepInputs inputs;
  inputs.save(sim_->model(), sim_->data());
  sim_->step();
  while (outOfRoom(sim_->data(), inputs)) {
    const MujocoRoom more = doubled(room_, mostRoom(plan_));
    if (more.contacts == room_.contacts && more.rows == room_.rows) {
      crowded_.add(1, site_);
      return;
    }
    std::ostringstream why;
    why << "at t = " << sim_->data()->time << " s the dynamics set's body touched the ground at more than "
        << room_.contacts << " points";
    if (stats_.instabilities > 0 || sim_->instabilities() > 0)
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
  // Counted per model: a rebuilt model's data counts from 0 again.
  if (const int bad = sim_->instabilities(); bad > countedInstabilities_) {
    unstable_.add(static_cast<uint64_t>(bad - countedInstabilities_), site_);
    stats_.instabilities += bad - countedInstabilities_;
    countedInstabilities_ = bad;
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

void DynamicsSet::contribute(Scene& scene) {
  const double time = target_.time;
  advanceTo(time);
  const bool first = stats_.rebuilds > 0 && firstMjcf_.empty() && sim_;
  // Read by the reposer as the frame's word ends, below.
  const mjData* s = nullptr;
  std::vector<int> contacts;
  if (sim_) {
    stateAt(time);
    s = sim_->scratch();
    for (int c = 0; c < s->ncon; ++c) {
      const mjContact& contact = s->contact[c];
      if (contact.geom1 != groundGeom_ && contact.geom2 != groundGeom_) continue;
      const int body = sim_->model()->geom_bodyid[contact.geom1 == groundGeom_ ? contact.geom2 : contact.geom1];
      if (planOfBody_[static_cast<std::size_t>(body)] >= 0) contacts.push_back(planOfBody_[static_cast<std::size_t>(body)]);
    }
    std::sort(contacts.begin(), contacts.end());
    contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
    draw_.setReposer([&](Skeleton& skeleton, std::vector<CreatureLimb>& limbs) {
      if (skeleton.joints.size() != skeletonBodies_) return;
      // Each joint to its body's place; its limbs move rigidly with it.
      std::vector<glm::dmat3> turns(skeleton.joints.size());
      std::vector<glm::dvec3> from(skeleton.joints.size());
      for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
        SceneJoint& joint = skeleton.joints[j];
        const int body = bodyIds_[j];
        if (body < 0) continue;
        const glm::dmat3 frame = frameOf(s, body);
        turns[j] = frame * glm::transpose(joint.orientation);
        from[j] = joint.position;
        joint.position = positionOf(s, body);
        joint.orientation = frame;
      }
      for (CreatureLimb& limb : limbs) {
        if (limb.joint < 0 || static_cast<std::size_t>(limb.joint) >= skeleton.joints.size()) continue;
        const std::size_t j = static_cast<std::size_t>(limb.joint);
        limb.start = skeleton.joints[j].position + turns[j] * (limb.start - from[j]);
        limb.frame = turns[j] * limb.frame;
      }
      skeleton.simulated = true;
      skeleton.contacts = contacts;
    });
  } else {
    draw_.setReposer({});
  }
  FrameTarget frame = target_;
  frame.time = time;
  replay(tape_, frame, draw_, stepStarts_);
  draw_.endWord();
  draw_.setReposer({});
  scene_.clear();
  draw_.contribute(scene_);
  scene_.time = time;

  if (sim_) {
    // The rods where the simulation has their bodies (a creature's own limbs are drawn above).
    for (std::size_t b = 0; b < plan_.bodies.size(); ++b) {
      const PlanBody& body = plan_.bodies[b];
      const int id = bodyIds_[b];
      if (id < 0) continue;
      const glm::dmat3 turn = frameOf(s, id) * glm::transpose(body.orientation);
      const glm::dvec3 at = positionOf(s, id);
      scene_.geometry.setMaterial(3);
      for (const PlanLimb& limb : body.limbs)
        if (limb.cylinder)
          scene_.geometry.addCylinder(at + turn * (limb.start - body.position), at + turn * (limb.end - body.position),
                                    limb.radius, false, turn * body.orientation[1]);
    }
    rodTips_.clear();
    for (const auto& [holder, tip] : rodTipsAtRest_) {
      if (holder < 0) continue;
      const PlanBody& body = plan_.bodies[static_cast<std::size_t>(holder)];
      const int id = bodyIds_[static_cast<std::size_t>(holder)];
      rodTips_.push_back(positionOf(s, id) + frameOf(s, id) * glm::transpose(body.orientation) * (tip - body.position));
    }
  }

  if (sim_) {
    // Where the body is: its first root, its centre of mass, its lowest joint.
    const mjModel* m = sim_->model();
    const glm::dvec3 root = positionOf(s, bodyIds_[0]);
    double mass = 0;
    glm::dvec3 centre(0.0);
    for (int b = 1; b < m->nbody; ++b) {
      mass += m->body_mass[b];
      centre += m->body_mass[b] * glm::dvec3(s->xipos[3 * b], s->xipos[3 * b + 1], s->xipos[3 * b + 2]);
    }
    const double height = (mass > 0 ? centre.y / mass : root.y) - physics_.ground;
    double lowest = std::numeric_limits<double>::infinity();
    for (const SceneJoint& joint : scene_.skeleton.joints) lowest = std::min(lowest, joint.position.y - physics_.ground);
    if (first) {
      stats_.rootStart = root;
      stats_.startHeight = height;
      stats_.lowest = lowest;
    }
    stats_.root = root;
    stats_.height = height;
    stats_.lowest = std::min(stats_.lowest, lowest);
  }
  if (first) {
    // The model as it stands at the first frame: its state as the keyframe MuJoCo resets to.
    const mjModel* m = sim_->model();
    const mjData* d = sim_->scratch();
    std::string key = "  <keyframe>\n    <key time=\"" + numbers(&d->time, 1) + "\" qpos=\"" + numbers(d->qpos, m->nq) +
                      "\" qvel=\"" + numbers(d->qvel, m->nv) + "\"";
    if (m->nu > 0) key += " ctrl=\"" + numbers(d->ctrl, m->nu) + "\"";
    key += "/>\n  </keyframe>\n";
    firstMjcf_ = mjcf_;
    firstMjcf_.insert(firstMjcf_.rfind("</mujoco>"), key);
  }
  scene.time = time;
  scene.append(scene_);
}

std::vector<ServoTarget> DynamicsSet::targets() const {
  std::vector<ServoTarget> out;
  if (!sim_) return out;
  for (const Hinge& hinge : hinges_)
    if (hinge.actuator >= 0) out.push_back({hinge.body, hinge.dof, sim_->data()->ctrl[hinge.actuator]});
  return out;
}

std::vector<std::filesystem::path> DynamicsSet::endFrame() {
  std::vector<std::filesystem::path> out;
  if (def_.writeMjcf && !firstMjcf_.empty() && framed_) {
    FrameTarget whole = target_;
    whole.frameCount = 1;
    const std::filesystem::path path = outputPath(whole, "xml");
    writeFileAtomically(path, [&](std::ostream& stream) { stream << firstMjcf_; });
    out.push_back(path);
    framed_ = false;
  }
  return out;
}

std::vector<SetWarning> DynamicsSet::takeWarnings() {
  std::vector<SetWarning> out = inner_.takeWarnings();
  for (auto& warning : out) {
    const std::string creature = "the creature set";
    if (warning.message.rfind(creature, 0) == 0) warning.message.replace(0, creature.size(), "the dynamics set");
  }
  // The replays repeat the word's own warnings.
  replay_.takeWarnings();
  draw_.takeWarnings();
  badArguments_.takeInto(out, "the dynamics set ignored " + std::to_string(badArguments_.count) +
                                  " of its commands with bad arguments: values not finite or out of range (the first here)");
  unstable_.takeInto(out, "MuJoCo found the simulation unstable " + std::to_string(unstable_.count) +
                              " times and reset it: a smaller #timestep or weaker servos (the first here)");
  crowded_.takeInto(out, "MuJoCo had no room for all contacts in " + std::to_string(crowded_.count) +
                             " steps, even at the most room the set gives (4 contacts a limb touching the ground): it dropped some (the first here)");
  return out;
}

}  // namespace ontogen
