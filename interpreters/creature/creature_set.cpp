#include "interpreters/creature/creature_set.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "interpreters/creature/two_bone_ik.h"
#include "interpreters/geometry/gc_mesher.h"
#include "model/random.h"

namespace ontogen {

namespace {

bool finite(std::span<const double> args) {
  return std::all_of(args.begin(), args.end(), [](double v) { return std::isfinite(v); });
}

// Turns a towards b by radians in their plane (a and b unit and perpendicular).
void rotate(glm::dvec3& a, glm::dvec3& b, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  const glm::dvec3 oldA = a;
  a = oldA * c + b * s;
  b = b * c - oldA * s;
}

// Frames are columns H, L, U; rotations keep them orthonormal (re-made from H and U).
void turn(glm::dmat3& frame, int from, int to, double radians) {
  rotate(frame[from], frame[to], radians);
  glm::dvec3 h = glm::normalize(frame[0]);
  glm::dvec3 l = glm::normalize(glm::cross(frame[2], h));
  frame = glm::dmat3(h, l, glm::cross(h, l));
}

// Rotates v about the unit axis by radians (Rodrigues).
glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& axis, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1 - c);
}

glm::dvec3 level(const glm::dvec3& v, const glm::dvec3& up) { return v - glm::dot(v, up) * up; }

constexpr double kHeldTolerance = 1e-9;  // radians a driver may overshoot without a warning

// Places past ±1e30 model units are refused, as the geometry set refuses shapes there
// (interpreters/geometry.cpp): the 32-bit floats of glTF and the joints' tracks hold up
// to 3.4e38, and differences taken between places must stay finite too.
constexpr double kMaxPlace = 1e30;

bool placeable(const glm::dvec3& p) {
  return std::abs(p.x) <= kMaxPlace && std::abs(p.y) <= kMaxPlace && std::abs(p.z) <= kMaxPlace;  // false for NaN
}
bool placeable(const glm::dmat3& frame) { return placeable(frame[0]) && placeable(frame[1]) && placeable(frame[2]); }

}  // namespace

CreatureSet::CreatureSet(const CreatureSetDef& def)
    : def_(def), output_(def.output), scene_{0, Geometry(MeshDef{}), {}, {}} {
  if (def.limbSides < 3 || def.limbSides > 1024) throw std::invalid_argument("limbSides must be 3..1024");
  if (def.limbSamples < 1 || def.limbSamples > 256) throw std::invalid_argument("limbSamples must be 1..256");
  if (!std::isfinite(def.ground)) throw std::invalid_argument("the ground's height must be finite");
}

bool CreatureSet::knows(std::string_view command) const { return findCreatureCommand(command) != nullptr; }

void CreatureSet::beginFrame(const FrameTarget& target) {
  target_ = target;
  time_ = target.time;
  scene_.clear();
  scene_.time = target.time;
  pose_ = Pose{};
  // Before any gait: heading along +x, up along +y (left is then -z).
  pose_.frame = pose_.restFrame = glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
  stack_.clear();
  creatures_.clear();
  legs_.clear();
  limbs_.clear();
  wordLimbs_.clear();
  stats_ = {};
  lastFrame_ = target.frame + 1 >= target.frameCount;
}

void CreatureSet::endWord() {
  if (reposer_) reposer_(scene_.skeleton, limbs_);
  const std::size_t joints = scene_.skeleton.joints.size();
  const bool grown = joints > mostJoints_ || mostJoints_ == 0;
  const bool wanted = def_.meshing == LimbMeshing::EveryFrame || grown ||
                      (def_.meshing == LimbMeshing::GrownAndLastFrame && lastFrame_);
  if (wanted) {
    mostJoints_ = std::max(mostJoints_, joints);
    Geometry& geometry = scene_.geometry;
    for (const PendingLimb& limb : limbs_) {
      geometry.setMaterial(limb.material);
      const auto first = static_cast<uint32_t>(geometry.triangleCount());
      placed_ = limbMesh(limb.length, limb.r0, limb.r1);
      for (glm::dvec3& v : placed_.positions) v = limb.start + limb.frame * v;
      for (glm::dvec3& n : placed_.normals) n = limb.frame * n;
      geometry.addMesh(placed_);
      const auto count = static_cast<uint32_t>(geometry.triangleCount()) - first;
      if (limb.joint >= 0 && count > 0) scene_.skeleton.skin.push_back({first, count, limb.joint});
    }
  }
  wordLimbs_.swap(limbs_);
  limbs_.clear();
}

void CreatureSet::beginCell(const CellContext& cell) {
  cellId_ = cell.id;
  jointsInCell_ = 0;
}

void CreatureSet::execute(std::string_view command, std::span<const double> args) {
  if (const CreatureCommand* found = findCreatureCommand(command)) run(*found, args);
}

void CreatureSet::executeCommand(int id, std::string_view command, std::span<const double> args) {
  const auto table = creatureCommands();
  if (id >= 0 && static_cast<std::size_t>(id) < table.size())
    run(table[id], args);
  else
    execute(command, args);
}

double CreatureSet::angle(double value) const { return def_.radians ? value : value * (std::numbers::pi / 180); }

// A degree of freedom of the joint being made, held inside the range given for it.
double CreatureSet::held(int dof, double value) {
  const Range& range = pose_.ranges[dof];
  if (!range.set) return value;
  const double kept = std::clamp(value, range.lo, range.hi);
  if (std::abs(kept - value) > kHeldTolerance) {
    clamped_.add(1, site_);
    ++stats_.clamped;
  }
  return kept;
}

int CreatureSet::addJoint(bool foot) {
  SceneJoint joint;
  // A joint per joint cell keeps the cell's id; a cell's later joints take ids made from it.
  joint.id = jointsInCell_ == 0 ? cellId_ : mixKey(cellId_, static_cast<uint64_t>(jointsInCell_));
  ++jointsInCell_;
  joint.parent = pose_.joint;
  const int index = static_cast<int>(scene_.skeleton.joints.size());
  joint.name = std::string(site_.cell.empty() ? "joint" : site_.cell) + "." + std::to_string(index);
  joint.position = pose_.position;
  joint.orientation = pose_.frame;
  joint.foot = foot;
  joint.segment = pose_.segment;
  if (pose_.leg >= 0) joint.side = legs_[pose_.leg].side;
  scene_.skeleton.joints.push_back(std::move(joint));
  pose_.joint = index;
  pose_.ranges = {};
  return index;
}

// Finite arguments can still place the turtle beyond any output (f(1e308) f(1e308), a
// gait whose walk has gone past 1e30 by the word's time): such a command is undone and
// counted with the bad arguments, so the set never writes a non-finite number.
void CreatureSet::run(const CreatureCommand& command, std::span<const double> args) {
  if (static_cast<int>(args.size()) < command.minArity || static_cast<int>(args.size()) > command.maxArity ||
      !finite(args)) {
    badArguments_.add(1, site_);
    return;
  }
  const Undo undo{pose_, scene_.skeleton.joints.size(), creatures_.size(), legs_.size(), limbs_.size()};
  runChecked(command, args);
  if (placeable(undo)) return;
  pose_ = undo.pose;
  scene_.skeleton.joints.resize(undo.joints);
  creatures_.resize(undo.creatures);
  legs_.resize(undo.legs);
  limbs_.resize(undo.limbs);
  stats_.creatures = static_cast<int>(creatures_.size());
  stats_.legs = static_cast<int>(legs_.size());
  badArguments_.add(1, site_);
}

bool CreatureSet::placeable(const Undo& undo) const {
  using ontogen::placeable;
  if (!placeable(pose_.position) || !placeable(pose_.restPosition) || !placeable(pose_.frame) ||
      !placeable(pose_.restFrame))
    return false;
  const auto& joints = scene_.skeleton.joints;
  for (std::size_t i = undo.joints; i < joints.size(); ++i)
    if (!placeable(joints[i].position) || !placeable(joints[i].orientation)) return false;
  for (std::size_t i = undo.creatures; i < creatures_.size(); ++i)
    if (!placeable(creatures_[i].root)) return false;
  for (std::size_t i = undo.legs; i < legs_.size(); ++i)
    if (!placeable(legs_[i].target) || !std::isfinite(legs_[i].kneeAngle)) return false;
  for (std::size_t i = undo.limbs; i < limbs_.size(); ++i)
    if (!placeable(limbs_[i].start) || !placeable(limbs_[i].frame) ||
        !placeable(limbs_[i].start + limbs_[i].length * limbs_[i].frame[0]))
      return false;
  return true;
}

void CreatureSet::runChecked(const CreatureCommand& command, std::span<const double> args) {
  Pose& p = pose_;
  switch (command.op) {
    case CreatureOp::Gait: startCreature(args); break;
    case CreatureOp::Range: {
      const int dof = static_cast<int>(args[0]);
      if (dof != args[0] || dof < 0 || dof > 2 || args[1] > args[2]) {
        badArguments_.add(1, site_);
        break;
      }
      p.ranges[dof] = {true, angle(args[1]), angle(args[2])};
      break;
    }
    case CreatureOp::Bend: {
      const double yaw = held(0, angle(args[0]));
      const double pitch = held(1, angle(args[1]));
      turn(p.frame, 0, 1, yaw);
      turn(p.frame, 0, 2, pitch);
      ++p.segment;
      p.leg = -1;
      addJoint();
      break;
    }
    case CreatureOp::Hinge:
      turn(p.frame, 0, 2, held(0, angle(args[0])));
      addJoint();
      break;
    case CreatureOp::Hip: hip(args); break;
    case CreatureOp::Knee: knee(); break;
    case CreatureOp::Foot: foot(); break;
    case CreatureOp::Limb: limb(args); break;
    case CreatureOp::Move:
      p.position += args[0] * p.frame[0];
      p.restPosition += args[0] * p.restFrame[0];
      break;
    case CreatureOp::TurnLeft:
    case CreatureOp::TurnRight:
    case CreatureOp::PitchDown:
    case CreatureOp::PitchUp:
    case CreatureOp::RollLeft:
    case CreatureOp::RollRight:
    case CreatureOp::TurnAround: {
      // The turtle's rotations (turtle_commands.h), to posed and rest frames alike.
      double a = command.op == CreatureOp::TurnAround ? std::numbers::pi : angle(args[0]);
      int from = 0, to = 1;
      switch (command.op) {
        case CreatureOp::TurnRight: a = -a; break;
        case CreatureOp::PitchDown: to = 2; a = -a; break;
        case CreatureOp::PitchUp: to = 2; break;
        case CreatureOp::RollLeft: from = 1; to = 2; a = -a; break;
        case CreatureOp::RollRight: from = 1; to = 2; break;
        default: break;
      }
      turn(p.frame, from, to, a);
      turn(p.restFrame, from, to, a);
      break;
    }
    case CreatureOp::Push: stack_.push_back(p); break;
    case CreatureOp::Pop:
      if (stack_.empty()) {
        badArguments_.add(1, site_);
        break;
      }
      p = stack_.back();
      stack_.pop_back();
      break;
    case CreatureOp::Color: {
      const double index = std::floor(args[0]);
      p.material = static_cast<uint32_t>(std::fmod(std::fmod(index, 16.0) + 16.0, 16.0));
      break;
    }
  }
}

// The root of a creature: level, on its walk at the word's time.
void CreatureSet::startCreature(std::span<const double> args) {
  GaitDef gait{.period = args[0], .duty = args[1], .stride = args[2], .lift = args[3], .height = args[4]};
  if (const char* error = gaitError(gait)) {
    // Named with its own reason: a gait refused leaves the whole creature unmade.
    if (badGaits_.count == 0) badGait_ = error;
    badGaits_.add(1, site_);
    return;
  }
  Creature creature;
  creature.gait = gait;
  const glm::dvec3 up(0, 1, 0);
  glm::dvec3 forward = level(pose_.frame[0], up);
  forward = glm::length(forward) > 1e-9 ? glm::normalize(forward) : glm::dvec3(1, 0, 0);
  creature.up = up;
  creature.forward = forward;
  creature.left = glm::cross(up, forward);
  glm::dvec3 start = level(pose_.position, up) + (def_.ground + gait.height) * up;
  creature.root = start + gait.speed() * time_ * forward;
  creatures_.push_back(creature);
  stats_.creatures = static_cast<int>(creatures_.size());
  stats_.distance = gait.speed() * time_;

  pose_.creature = static_cast<int>(creatures_.size()) - 1;
  pose_.position = pose_.restPosition = creature.root;
  pose_.frame = pose_.restFrame = glm::dmat3(forward, creature.left, up);
  pose_.joint = -1;
  pose_.leg = -1;
  pose_.segment = -1;
  addJoint();
}

void CreatureSet::hip(std::span<const double> args) {
  const double phase = args[0], upper = args[1], lower = args[2], reach = args[3];
  if (!(upper > 0) || !(lower > 0)) {
    badArguments_.add(1, site_);
    return;
  }
  Pose& p = pose_;
  Leg leg;
  leg.upper = upper;
  leg.lower = lower;
  const double swivel = held(2, angle(args[4]));
  if (p.creature < 0) {
    // No gait to follow: the leg hangs straight along H.
    legless_.add(1, site_);
    leg.target = p.position + (upper + lower) * p.frame[0];
  } else {
    const Creature& creature = creatures_[p.creature];
    const double lift = args.size() > 5 ? args[5] : creature.gait.lift;
    // The neutral foot point: reach out along the resting leg, made level, on the ground.
    const glm::dvec3 out = level(p.restFrame[0], creature.up);
    glm::dvec3 neutral = p.restPosition + (glm::length(out) > 1e-9 ? reach * glm::normalize(out) : glm::dvec3(0.0));
    neutral -= (glm::dot(neutral, creature.up) - def_.ground) * creature.up;
    const double lateral = glm::length(out) > 1e-9 ? glm::dot(out, creature.left)
                                                   : glm::dot(p.restPosition - creature.root, creature.left);
    leg.side = lateral > 1e-9 ? BodySide::Left : lateral < -1e-9 ? BodySide::Right : BodySide::None;
    leg.target = footPosition(creature.gait, phase, lift, time_, neutral, creature.forward, creature.up);
  }
  // The knee goes towards U, turned by the swivel about the hip-foot line.
  glm::dvec3 line = leg.target - p.position;
  line = glm::length(line) > 1e-12 ? glm::normalize(line) : p.frame[0];
  const glm::dvec3 pole = rotateAbout(p.frame[2], line, swivel);
  TwoBoneLeg solved = solveTwoBone(p.position, leg.target, upper, lower, pole);
  // The hip's swing (about U) and lift (towards U), held in their ranges.
  const glm::dvec3 h0 = p.frame[0], l0 = p.frame[1], u0 = p.frame[2];
  const glm::dvec3& u = solved.upperDirection;
  const double swing = std::atan2(glm::dot(u, l0), glm::dot(u, h0));
  const double lift = std::asin(std::clamp(glm::dot(u, u0), -1.0, 1.0));
  const double heldSwing = held(0, swing), heldLift = held(1, lift);
  glm::dvec3 heading = u, kneeSide = solved.kneeSide;
  if (heldSwing != swing || heldLift != lift) {
    heading = std::cos(heldLift) * (std::cos(heldSwing) * h0 + std::sin(heldSwing) * l0) + std::sin(heldLift) * u0;
    glm::dvec3 across = kneeSide - glm::dot(kneeSide, heading) * heading;
    kneeSide = glm::length(across) > 1e-9 ? glm::normalize(across) : u0;
  }
  leg.kneeAngle = solved.kneeAngle;
  p.frame = glm::dmat3(heading, glm::cross(kneeSide, heading), kneeSide);
  legs_.push_back(leg);
  stats_.legs = static_cast<int>(legs_.size());
  p.leg = static_cast<int>(legs_.size()) - 1;
  addJoint();
}

void CreatureSet::knee() {
  if (pose_.leg < 0) {
    badArguments_.add(1, site_);
    return;
  }
  // The lower limb turns away from the knee's side: a pitch down by the knee's angle.
  turn(pose_.frame, 0, 2, -held(0, legs_[pose_.leg].kneeAngle));
  addJoint();
}

void CreatureSet::foot() {
  const int index = addJoint(true);
  if (pose_.leg < 0) return;
  const Leg& leg = legs_[pose_.leg];
  const glm::dvec3 at = scene_.skeleton.joints[index].position;
  if (glm::length(at - leg.target) > 1e-6 * (leg.upper + leg.lower)) {
    unreached_.add(1, site_);
    ++stats_.unreached;
  }
}

void CreatureSet::limb(std::span<const double> args) {
  const double length = args[0], r0 = args[1], r1 = args.size() > 2 ? args[2] : args[1];
  if (!(length > 0) || r0 < 0 || r1 < 0) {
    badArguments_.add(1, site_);
    return;
  }
  Pose& p = pose_;
  const glm::dvec3 start = p.position, end = p.position + length * p.frame[0];
  if (r0 == 0 && r1 == 0) {
    scene_.geometry.setMaterial(p.material);
    scene_.geometry.addSegment(start, end);
  } else {
    limbs_.push_back({start, p.frame, length, r0, r1, p.material, p.joint});
  }
  p.position = end;
  p.restPosition += length * p.restFrame[0];
}

// A generalized cylinder through base, middle and tip, swelling a little between, along
// +x with its side along +y: the frame's H and L.
const Mesh& CreatureSet::limbMesh(double length, double r0, double r1) {
  const std::array<double, 3> key{length, r0, r1};
  auto found = limbMeshes_.find(key);
  if (found != limbMeshes_.end()) return found->second;
  if (limbMeshes_.size() >= kLimbShapes) limbMeshes_.clear();
  const glm::dvec3 side(0, 1, 0);
  const double middle = 1.15 * std::max(r0, r1);
  const std::array<GcControlPoint, 3> points{GcControlPoint{glm::dvec3(0.0), side, r0, nullptr},
                                              GcControlPoint{glm::dvec3(length / 2, 0, 0), side, middle, nullptr},
                                              GcControlPoint{glm::dvec3(length, 0, 0), side, r1, nullptr}};
  return limbMeshes_.emplace(key, meshGeneralizedCylinder(points, GcDef{def_.limbSamples, def_.limbSides, true}))
      .first->second;
}

void CreatureSet::contribute(Scene& scene) {
  scene.time = scene_.time;
  scene.append(scene_);
}

std::vector<std::filesystem::path> CreatureSet::endFrame() { return output_.write(scene_, target_); }

std::vector<SetWarning> CreatureSet::takeWarnings() {
  std::vector<SetWarning> out;
  badArguments_.takeInto(out, "the creature set ignored " + std::to_string(badArguments_.count) +
                                  " commands with bad arguments: values not finite or out of range, a knee without a "
                                  "hip, an unmatched ']' (the first here)");
  clamped_.takeInto(out, "the creature set held " + std::to_string(clamped_.count) +
                             " joint angles inside their ranges (the first here)");
  unreached_.takeInto(out, "the creature set counted " + std::to_string(unreached_.count) +
                               " feet that could not reach where the gait puts them (the first here)");
  badGaits_.takeInto(out, "the creature set made no creature of " + std::to_string(badGaits_.count) +
                              (badGaits_.count == 1 ? " gait" : " gaits") + " out of range: " +
                              (badGait_ ? badGait_ : "") + " (the first here)");
  legless_.takeInto(out, "the creature set made " + std::to_string(legless_.count) +
                             " legs outside any creature (no gait before them), hanging straight (the first here)");
  return out;
}

}  // namespace ontogen
