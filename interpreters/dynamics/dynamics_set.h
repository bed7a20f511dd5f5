#pragma once
// The "dynamics" interpretation set: the creature set's body (interpreters/creature/)
// living under physics, simulated by MuJoCo. It runs the creature set's commands on an
// inner creature set and keeps the word as a tape of its cells and commands. At the end
// of a word it makes the word's body plan (body_plan.h), a rigid body per joint, and its
// MuJoCo model (mjcf_builder.h); each hinge gets a position servo whose target, at every
// step of the simulation, is the angle the kinematic pose asks at that time: the tape
// replayed at the step's time, so the gait's inverse kinematics follows the simulated
// time while the drivers (the cells' arguments) hold the values of the last word seen.
//
// A run feeds the set the word at every instant of the development's step grid
// (InterpretationSet::simulates), never at frames: the simulation steps at its own fixed
// step (#timestep) from the first word with joints, and a frame reads its state at the
// frame's time from a copy (a partial step from the last step before it), so which
// frames are drawn never changes the motion. A word whose body differs from the model's
// (joints added or removed) rebuilds the model at that word's kinematic pose.
//
// A frame is the inner creature set's scene of the tape at the frame's time, every joint
// and limb moved to where the simulation has its body; the skeleton is marked simulated
// and lists the joints whose limbs touch the ground.
//
// Its parts: dynamics_set.cpp reads the word into its tape and body plan; dynamics_rods.cpp
// makes the plants' rods and their wind; dynamics_build.cpp makes the model and carries the
// state over; dynamics_servos.cpp sets the servos' targets; dynamics_step.cpp steps the
// simulation; dynamics_frame.cpp draws a frame from it.

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "interpreters/creature/creature_set.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/dynamics/body_plan.h"
#include "interpreters/dynamics/mjcf_builder.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/scene.h"

namespace ontogen {

class MujocoModel;

struct DynamicsSetDef {
  bool radians = false;     ///< angles in radians (#radians), else degrees
  LimbMeshing meshing = LimbMeshing::EveryFrame;  ///< as the creature set's
  PhysicsDef physics{};     ///< timestep (#timestep) and the defaults of the set's commands
  bool writeMjcf = false;   ///< endFrame() writes DIR/<stem>.xml, the model of the first frame
  /// The memory limit (--max-memory) MuJoCo's room for contacts (mujocoRoomBytes) must
  /// fit in before a model is made: passing it is a LimitError. 0: none.
  uint64_t maxMemoryBytes = 0;
};

/// What the simulation did up to the last frame drawn, for measures and tests.
struct DynamicsStats {
  bool simulating = false;   ///< a model exists
  int rebuilds = 0;          ///< models made (the first counts)
  int carried = 0;           ///< bodies whose state a rebuilt model took over from the one before
  double simulatedTime = 0;  ///< seconds stepped in all
  glm::dvec3 rootStart{0.0};  ///< the first root body's place at the first frame
  glm::dvec3 root{0.0};       ///< and at the last
  double startHeight = 0;     ///< the body's centre of mass above the ground at the first frame
  double height = 0;          ///< and at the last
  double lowest = 0;          ///< the lowest height above the ground any joint had at a frame
  double energy = 0;          ///< the servos' work, |torque x angular speed| summed over steps
  double slip = 0;            ///< distance contact points slid along the ground, summed
  /// Steps at which MuJoCo found the state bad (not finite, or past its bound of 1e10 on
  /// positions, speeds and accelerations: an unstable simulation) and reset it.
  int instabilities = 0;
  int roomGrowths = 0;        ///< steps taken again with twice the contacts' and constraints' room
};

/// What a joint's servo is asked: the angle of one of its degrees of freedom in the
/// kinematic pose (radians, as MuJoCo's hinge measures it).
struct ServoTarget {
  int joint = 0;  ///< in the skeleton's order
  int dof = 0;
  double angle = 0;
};

class DynamicsSet : public InterpretationSet {
 public:
  /// The rods' springs' damping, times their stiffness, seconds, unless damping() says.
  static constexpr double kRodDamping = 0.01;
  /// The air's density and a rod's drag coefficient across the air (a long cylinder's).
  static constexpr double kAirDensity = 1.2, kDragCoefficient = 1.2;
  /// How often, in seconds of simulated time, the servos' targets are taken from the
  /// kinematic pose, unless control() says: they are followed linearly between.
  static constexpr double kControlPeriod = 0.01;

  /// Throws std::invalid_argument when def is out of range.
  explicit DynamicsSet(const DynamicsSetDef& def = {});
  ~DynamicsSet() override;

  std::string_view name() const override { return "dynamics"; }
  bool knows(std::string_view command) const override;
  bool simulates() const override { return true; }
  /// Cells with no `interpret dynamics` block run their `interpret creature` one.
  std::string_view alsoReads() const override { return "creature"; }
  bool drawsScene() const override { return true; }
  void beginFrame(const FrameTarget& target) override;
  void beginWord(double time) override;
  void beginCell(const CellContext& cell) override;
  void execute(std::string_view command, std::span<const double> args) override;
  /// `id` indexes dynamicsCommands() followed by creatureCommands().
  void executeCommand(int id, std::string_view command, std::span<const double> args) override;
  /// Simulates up to the word's time with the last word, then takes this one.
  void endWord() override;
  /// Simulates up to the frame's time and draws the body where the simulation has it.
  void contribute(Scene& scene) override;
  /// Writes what the set keeps of the whole run (the MJCF, when asked); returns the paths.
  std::vector<std::filesystem::path> endFrame() override;
  std::vector<SetWarning> takeWarnings() override;

  const DynamicsStats& stats() const { return stats_; }
  /// The servos' targets at the start of the last step taken (none before a model exists).
  std::vector<ServoTarget> targets() const;
  /// The tip of each rod of the model (in the order the word drew them) at the last frame drawn.
  const std::vector<glm::dvec3>& rodTips() const { return rodTips_; }
  /// The scene of the last frame drawn.
  const Scene& scene() const { return scene_; }
  /// The MJCF of the model at the first frame drawn, with its state as a keyframe ("" before).
  const std::string& firstFrameMjcf() const { return firstMjcf_; }

 private:
  // An entry of a word's tape: a cell begins, or a creature command runs.
  struct TapeEntry {
    bool cell = false;
    CellContext context;
    InstructionSite site;
    int command = -1;  // index in creatureCommands()
    std::vector<double> args;
  };
  // What a joint command made of the turtle it started from.
  struct JointStart {
    JointKind kind = JointKind::Weld;
    glm::dmat3 base{1.0};
    std::array<CreatureRange, 3> ranges{};
  };
  // Replays the tape as a frame at target.time into `set`, collecting the joints' starts.
  void replay(const std::vector<TapeEntry>& tape, const FrameTarget& target, CreatureSet& set,
              std::vector<JointStart>& starts);
  void runCreature(CreatureSet& set, int command, std::span<const double> args, std::vector<JointStart>& starts);
  BodyPlan planOf(const CreatureSet& set, const std::vector<JointStart>& starts) const;
  // A rod the word drew, and what a path's rods are made of ([ pushes it).
  struct RodSpec {
    uint64_t id = 0;
    int parent = -1;  // index in the word's rods; -1: fixed at its base
    int joint = -1;   // the creature's joint the turtle stood on, which a first rod hangs from; -1: none
    glm::dvec3 base{0.0};
    glm::dmat3 frame{1.0};
    double length = 0, radius = 0, density = 0, stiffness = 0;
    int segments = 4;
  };
  struct RodPath {
    int rod = -1;
    double stiffness = 0;
    int segments = 4;
  };
  struct Air {
    glm::dvec3 speed{0.0};
    double gust = 0, period = 4;
  };
  void runOwn(DynamicsOp op, std::span<const double> args);
  // Appends the rods' bodies to the plan (after the skeleton's).
  void addRods(BodyPlan& plan, const std::vector<RodSpec>& rods) const;
  // What a body of a model keeps into the next one (build), found by its id.
  struct Carried;
  // Each free joint of the new model from what its body, or one of its tree, kept.
  void placeFreeBodies(const std::unordered_map<uint64_t, Carried>& carried);
  void build(const BodyPlan& plan, double time);
  void applyWind(double time);
  void advanceTo(double time);
  // One step; taken again in a model with more room while MuJoCo had too little.
  void stepWithRoom();
  // Throws LimitError when MuJoCo's data for `room` would not fit in the memory limit;
  // `why` says what asks for it.
  void checkRoomMemory(MujocoRoom room, const std::string& why) const;
  void setControls(double time);
  // The servos' targets (one per actuated hinge, in hinges_' order) from the tape replayed
  // at `time`; false when the tape no longer makes the model's joints.
  bool poseTargets(double time, std::vector<double>& out);
  double stepTime(long steps) const { return start_ + static_cast<double>(steps) * physics_.timestep; }
  // The state at `time` (not before the last step) in scratch_, its kinematics computed.
  void stateAt(double time);

  DynamicsSetDef def_;
  CreatureSet inner_;   // runs each word as it comes
  CreatureSet replay_;  // the tape at each step's time
  CreatureSet draw_;    // the tape at each frame's time, meshed
  std::vector<TapeEntry> tape_, wordTape_;  // the last word taken; the word being read
  std::vector<JointStart> starts_, stepStarts_;
  PhysicsDef physics_, wordPhysics_;
  double wordTime_ = 0;
  double tapeTime_ = 0;

  std::unique_ptr<MujocoModel> sim_;
  BodyPlan plan_;
  std::string mjcf_;
  double start_ = 0;   // the model's first instant, seconds
  long steps_ = 0;     // taken since
  struct Hinge {
    int body = 0, dof = 0, qpos = 0, dof_address = 0, actuator = -1;
    CreatureRange range;
  };
  std::vector<Hinge> hinges_;
  std::vector<RodSpec> wordRods_, rods_;  // of the word being read; of the model's word
  RodPath rodPath_;
  std::vector<RodPath> rodStack_;
  uint64_t cellId_ = 0;
  int rodsInCell_ = 0;
  Air wordWind_, wind_;
  double wordDamping_ = kRodDamping, damping_ = kRodDamping;
  double wordControl_ = kControlPeriod, control_ = kControlPeriod;
  // The targets at the control grid's knot before the last step and at the one after it
  // (stale after a new tape or model).
  struct Knot {
    bool valid = false;
    std::vector<double> targets;
  };
  long knot_ = 0;
  bool knotsStale_ = true;
  Knot atKnot_, atNextKnot_;
  std::vector<double> towardsNextKnot_;  // per servo, from its target at atKnot_ to atNextKnot_'s
  std::size_t skeletonBodies_ = 0;  // the plan's bodies before its rods'
  struct Drag {
    int body = 0;  // MuJoCo's
    double radius = 0, length = 0;
  };
  std::vector<Drag> drags_;
  std::vector<std::pair<int, glm::dvec3>> rodTipsAtRest_;  // per rod: its plan body, its tip at rest
  std::vector<glm::dvec3> rodTips_;
  std::vector<int> bodyIds_;   // MuJoCo's body of each plan body
  std::vector<int> planOfBody_;  // the plan body of each MuJoCo body (-1: the world)
  int groundGeom_ = -1;
  MujocoRoom room_;

  FrameTarget target_;
  bool framed_ = false;
  Scene scene_;
  std::string firstMjcf_;
  std::vector<std::filesystem::path> written_;
  DynamicsStats stats_;
  WarningCounter badArguments_;
  WarningCounter unstable_;
  WarningCounter crowded_;
};

}  // namespace ontogen
