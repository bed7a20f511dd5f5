#pragma once
// The "physics" interpretation set: paper 003's design models of rod trees. It runs the
// geometry set's turtle (every turtle command) and the commands of physics_commands.h;
// each rod (rod, F, cC) is a straight cylinder from the turtle, its base, to where the
// turtle moves, its tip. A rod hangs from the rod before it on its path in the word
// (a branch [ ] from the rod before its [): the axial tree of core/parents.h restricted
// to rods, keyed by the cells' stable ids (rod_table.h). After the word the set solves
// the rigid statics (rigid_statics.h) and, when the program asks with elastic(n), the
// elastic model (elastic_rods.h); it draws the rods (deflected when elastic) and, at each
// rod's base joint, an arrow for the force and a double arrow for the moment, starting
// from the joint as the paper draws them, coloured by magnitude, and the external loads
// as thick arrows from where they act. The result of the
// frame (frame()) is what `ontogen statics` prints.
//
// Units: metres, kilograms, seconds, newtons; g = 9.81 m/s^2 down the world's up axis, +y.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "interpreters/formats/scene_output.h"
#include "interpreters/geometry/turtle.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/physics/elastic_rods.h"
#include "interpreters/physics/force_arrows.h"
#include "interpreters/physics/physics_commands.h"
#include "interpreters/physics/physics_frame.h"
#include "interpreters/physics/rod_table.h"
#include "interpreters/scene.h"

namespace ontogen {

struct PhysicsSetDef {
  TurtleDef turtle{};       ///< step, angles, initial radius (the program's #length, #angle, #radius)
  MeshDef mesh{};           ///< tessellation of the rods and arrows
  double g = kGravity;      ///< m/s^2
  SceneOutputDef output{};  ///< what endFrame() writes when the set is used on its own
};

class PhysicsSet : public InterpretationSet {
 public:
  /// Throws std::invalid_argument when def is out of range.
  explicit PhysicsSet(const PhysicsSetDef& def = {});

  std::string_view name() const override { return "physics"; }
  bool knows(std::string_view command) const override;
  void beginFrame(const FrameTarget& target) override;
  void beginCell(const CellContext& cell) override;
  void execute(std::string_view command, std::span<const double> args) override;
  /// `id` indexes physicsCommands(), then turtleCommands() after them (physicsCommandInfo).
  void executeCommand(int id, std::string_view command, std::span<const double> args) override;
  /// Solves the frame's statics (and the elastic model when asked).
  void endWord() override;
  std::vector<std::filesystem::path> endFrame() override;
  bool drawsScene() const override { return true; }
  void contribute(Scene& scene) override;
  std::vector<SetWarning> takeWarnings() override;

  /// The frame's rods and their results, after the word.
  const PhysicsFrame& frame() const { return frame_; }
  /// The relationship and design-model tables.
  const RodTable& table() const { return table_; }
  /// The answers to the word's query modules ?F, ?M and ?D after the word: by the query
  /// cell's id, the force, moment or deflection of the rod before it on its path (a
  /// query with no rod before it has no answer).
  const std::unordered_map<uint64_t, Eigen::Vector3d>& queryAnswers() const { return answers_; }
  /// The arrows of the frame, after it is drawn (contribute or endFrame).
  const std::vector<DrawnArrow>& arrows() const { return arrows_; }
  /// The scene of the frame being drawn, or of the last one.
  const Scene& scene() const { return scene_; }

 private:
  // What [ saves besides the turtle's own state.
  struct Attributes {
    double density = 1;     // kg/m^3
    double young = 0;       // Pa; 0: none
    double stiffness = 0;   // N m^2; 0: from young, else rigid
    uint64_t rod = kNoParentRod;  // the last rod on this path
  };

  void runTurtle(const TurtleCommand& command, std::span<const double> args);
  void runPhysics(const PhysicsCommand& command, std::span<const double> args);
  void addRod(const glm::dvec3& base, double radius, double density);
  void solve();
  void answerQueries();
  void draw();

  // A query module met in the word: its cell, the rod before it, and what it asks.
  struct NotedQuery {
    uint64_t cell;
    uint64_t rod;
    char kind;  // 'F', 'M' or 'D'
  };

  PhysicsSetDef def_;
  SceneOutput output_;
  Turtle turtle_;
  Geometry scratch_;  // what the turtle's F would draw: the set draws its rods itself
  Scene scene_;
  FrameTarget target_;
  RodTable table_;
  PhysicsFrame frame_;
  std::vector<DrawnArrow> arrows_;
  std::vector<NotedQuery> queries_;
  std::unordered_map<uint64_t, Eigen::Vector3d> answers_;
  std::vector<Eigen::Vector3d> drawnShape_;  // per rod 2 n + 1 points when elastic
  Attributes attributes_;
  std::vector<Attributes> stack_;
  Eigen::Vector3d pendingLoad_ = Eigen::Vector3d::Zero();
  double pendingLoadAt_ = 1;
  bool hasPendingLoad_ = false;
  int segments_ = 0;  // elastic(n); 0: rigid
  double forceScale_ = 0, momentScale_ = 0;
  uint64_t cellId_ = 0;
  int rodsInCell_ = 0;
  bool drawn_ = false;
  WarningCounter badArguments_;
  WarningCounter unconverged_;
  WarningCounter unmatchedPops_;
};

}  // namespace ontogen
