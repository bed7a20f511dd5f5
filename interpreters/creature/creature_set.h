#pragma once
// The "creature" interpretation set: an articulated turtle that builds walking creatures
// (paper 000, section 5.3; paper 002, section 3, Fig. 4). Cells make joints (`bend`,
// `hinge`, `hip`, `knee`, `foot`) and the rigid limbs between them (`limb`, generalized
// cylinders); each joint is a SceneJoint keyed by its cell's stable id, hanging from the
// joint before it in the word (a branch keeps its joint), so forward kinematics composes
// every joint's rotation with its parents'. `gait` starts a creature: its root travels
// along the ground at the speed its stance feet push (gait.h), and each `hip` solves its
// leg (two_bone_ik.h) for where its foot is in the gait: planted where it touched down,
// or on its arc to the next foothold. The drivers of the joints are the cells' own
// development: the arguments of `bend` and `hinge`, the `hip`'s swivel and lift.
//
// Everything a frame holds follows from the word and its time alone, so a walk is the
// same whatever frames are drawn. The set draws a scene (its limbs, posed) with its
// skeleton (interpreters/scene.h); the output stage writes it, as a skinned glTF among
// others (formats/skinned_glb_writer.h).

#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "interpreters/creature/creature_commands.h"
#include "interpreters/creature/gait.h"
#include "interpreters/formats/scene_output.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/scene.h"

namespace ontogen {

/// Which frames the set meshes its limbs in. The skeleton is posed in every frame; the
/// skinned glTF needs the limbs of one frame only (the one with the most joints), a
/// picture of the last frame those of the last.
enum class LimbMeshing {
  EveryFrame,         ///< for per-frame outputs (obj, svg, ply, png-frames, mp4)
  GrownAndLastFrame,  ///< glb and png: frames with more joints than any before, and the last
  GrownFrames,        ///< glb and joints only
};

struct CreatureSetDef {
  bool radians = false;     ///< angles in radians (#radians), else degrees
  LimbMeshing meshing = LimbMeshing::EveryFrame;
  double ground = 0;        ///< the ground's height (world y), model units
  int limbSides = 12;       ///< points around a limb's cross-section (3..1024)
  int limbSamples = 4;      ///< rings of a limb between two of its control points (1..256)
  SceneOutputDef output{};  ///< what endFrame() writes when the set is used on its own
};

/// A rigid limb of a word: a generalized cylinder from start along the frame's H.
struct CreatureLimb {
  glm::dvec3 start{0.0};  ///< world position of its base, model units
  glm::dmat3 frame{1.0};  ///< world frame, columns H, L, U
  double length = 0, r0 = 0, r1 = 0;  ///< model units
  uint32_t material = 0;
  int joint = -1;  ///< index in the skeleton of the joint it moves with; -1: none
};

/// A degree of freedom's range, radians, as `range` gives it.
struct CreatureRange {
  bool set = false;
  double lo = 0, hi = 0;  ///< radians
};

/// Moves a word's joints and limbs before its limbs are meshed (a simulation posing the
/// body where its physics put it); limbs name their joints by index.
using CreatureReposer = std::function<void(Skeleton&, std::vector<CreatureLimb>&)>;

/// What the set saw in a frame, for tests and reports.
struct CreatureFrameStats {
  int creatures = 0;
  int legs = 0;
  double distance = 0;      ///< walked by the last creature since time 0, model units
  uint64_t clamped = 0;     ///< joint angles held inside their ranges
  uint64_t unreached = 0;   ///< feet that could not reach where the gait puts them
};

class CreatureSet : public InterpretationSet {
 public:
  /// Throws std::invalid_argument when def is out of range.
  explicit CreatureSet(const CreatureSetDef& def = {});

  std::string_view name() const override { return "creature"; }
  bool knows(std::string_view command) const override;
  void beginFrame(const FrameTarget& target) override;
  void beginWord(double time) override { time_ = time; }
  void beginCell(const CellContext& cell) override;
  void execute(std::string_view command, std::span<const double> args) override;
  /// `id` indexes creatureCommands().
  void executeCommand(int id, std::string_view command, std::span<const double> args) override;
  std::vector<std::filesystem::path> endFrame() override;
  /// Meshes the word's limbs (when this frame needs them).
  void endWord() override;
  bool drawsScene() const override { return true; }
  void contribute(Scene& scene) override;
  std::vector<SetWarning> takeWarnings() override;

  /// The scene of the frame being drawn, or of the last one.
  const Scene& scene() const { return scene_; }
  const CreatureFrameStats& stats() const { return stats_; }
  /// The ground's height (world y), model units.
  double ground() const { return def_.ground; }
  /// Where the turtle stands now (world, model units), its frame (columns H, L, U) and
  /// the index of the joint it hangs from (-1: none): what a command about to run starts from.
  const glm::dvec3& turtlePosition() const { return pose_.position; }
  const glm::dmat3& turtleFrame() const { return pose_.frame; }
  int turtleJoint() const { return pose_.joint; }
  /// The ranges the next joint's degrees of freedom will be held in.
  const std::array<CreatureRange, 3>& turtleRanges() const { return pose_.ranges; }
  /// Called at the end of every word before its limbs are meshed (empty: none).
  void setReposer(CreatureReposer reposer) { reposer_ = std::move(reposer); }
  /// The limbs of radius above 0 of the last word, in the order drawn (kept until the next frame).
  const std::vector<CreatureLimb>& wordLimbs() const { return wordLimbs_; }

 private:
  using Range = CreatureRange;
  // Where the turtle is, as posed and at rest (every driven angle 0: where the gait's
  // neutral foot points come from), and what it hangs from.
  struct Pose {
    glm::dvec3 position{0.0};
    glm::dmat3 frame{1.0};  // columns H, L, U
    glm::dvec3 restPosition{0.0};
    glm::dmat3 restFrame{1.0};
    int joint = -1;
    int creature = -1;
    int leg = -1;
    int segment = -1;
    uint32_t material = 0;
    std::array<Range, 3> ranges{};
  };
  struct Creature {
    GaitDef gait;
    glm::dvec3 forward{1, 0, 0}, up{0, 1, 0}, left{0, 0, -1};
    glm::dvec3 root{0.0};
  };
  using PendingLimb = CreatureLimb;
  struct Leg {
    double upper = 1, lower = 1;
    glm::dvec3 target{0.0};
    double kneeAngle = 0;
    BodySide side = BodySide::None;
  };

  void run(const CreatureCommand& command, std::span<const double> args);
  void runChecked(const CreatureCommand& command, std::span<const double> args);
  // What a command may add, to undo it: the sizes of what it appends to.
  struct Undo {
    Pose pose;
    std::size_t joints = 0, creatures = 0, legs = 0, limbs = 0;
  };
  /// The command since `undo` placed nothing beyond what outputs can hold.
  bool placeable(const Undo& undo) const;
  double angle(double value) const;
  double held(int dof, double value);
  int addJoint(bool foot = false);
  void startCreature(std::span<const double> args);
  void hip(std::span<const double> args);
  void knee();
  void foot();
  void limb(std::span<const double> args);

  // A limb's mesh, made once per shape along +x and placed by each frame's pose (paper 000:
  // the limbs are rigid, "the geometric data can be cached"). At most kLimbShapes shapes.
  const Mesh& limbMesh(double length, double r0, double r1);
  static constexpr std::size_t kLimbShapes = 4096;
  std::map<std::array<double, 3>, Mesh> limbMeshes_;
  Mesh placed_;
  std::vector<PendingLimb> limbs_;  // of the word being drawn, meshed at its end
  std::vector<CreatureLimb> wordLimbs_;  // of the last word
  std::size_t mostJoints_ = 0;      // the most joints a meshed frame had
  bool lastFrame_ = false;
  CreatureReposer reposer_;

  CreatureSetDef def_;
  SceneOutput output_;
  Scene scene_;
  FrameTarget target_;
  double time_ = 0;
  Pose pose_;
  std::vector<Pose> stack_;
  std::vector<Creature> creatures_;
  std::vector<Leg> legs_;
  uint64_t cellId_ = 0;
  int jointsInCell_ = 0;
  CreatureFrameStats stats_;
  WarningCounter badArguments_;
  WarningCounter clamped_;
  WarningCounter unreached_;
  WarningCounter legless_;
  WarningCounter badGaits_;
  const char* badGait_ = nullptr;  // why the first gait counted in badGaits_ was refused
};

}  // namespace ontogen
