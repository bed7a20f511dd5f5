#include "interpreters/dynamics/dynamics_set.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "interpreters/creature/creature_commands.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/dynamics/mujoco_model.h"
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
    case DynamicsOp::Solver:
      bad = args[0] != std::floor(args[0]) || !(args[0] >= 1 && args[0] <= kMostSolverIterations);
      if (bad) break;
      next.iterations = static_cast<int>(args[0]);
      if (args.size() > 1) next.tolerance = args[1];
      break;
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
  const bool physicsChanged =
      wordPhysics_ != physics_ || wordDamping_ != damping_ || wordRods_.size() != rods_.size();
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
  unstable_.takeInto(out, "MuJoCo found the simulation unstable at " + std::to_string(unstable_.count) +
                              " steps and reset it: a smaller #timestep or weaker servos (the first here)");
  crowded_.takeInto(out, "MuJoCo had no room for all contacts in " + std::to_string(crowded_.count) +
                             " steps, even at the most room the set gives (4 contacts a limb touching the ground): it dropped some (the first here)");
  return out;
}

}  // namespace ontogen
