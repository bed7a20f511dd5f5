#include "interpreters/geometry/turtle_queries.h"

#include <unordered_map>

#include "core/world.h"
#include "interpreters/interpret.h"
#include "interpreters/interpretation_set.h"

namespace ontogen {

namespace {

// Runs the turtle over the word like the geometry set, and notes its frame at every
// query module it meets.
class QueryingTurtle final : public InterpretationSet {
 public:
  explicit QueryingTurtle(const TurtleDef& def) : turtle_(def) {}
  // The geometry set's name: the cells' `interpret geometry` blocks run here too.
  std::string_view name() const override { return "geometry"; }
  bool knows(std::string_view command) const override { return findTurtleCommand(command) != nullptr; }
  void beginFrame(const FrameTarget&) override { turtle_.reset(); }
  void beginCell(const CellContext& cell) override { cell_ = cell.id; }
  void execute(std::string_view command, std::span<const double> args) override {
    if (const TurtleCommand* found = findTurtleCommand(command)) run(*found, args);
  }
  void executeCommand(int id, std::string_view command, std::span<const double> args) override {
    const auto table = turtleCommands();
    if (id >= 0 && static_cast<size_t>(id) < table.size())
      run(table[id], args);
    else
      execute(command, args);
  }
  std::vector<std::filesystem::path> endFrame() override { return {}; }

  /// The frame vector noted for each query cell, by id.
  const std::unordered_map<uint64_t, glm::dvec3>& noted() const { return noted_; }

 private:
  void run(const TurtleCommand& command, std::span<const double> args) {
    if (command.op == TurtleOp::Query) {
      const TurtleState& s = turtle_.state();
      const char kind = command.name[1];
      noted_[cell_] = kind == 'P' ? s.position : kind == 'H' ? s.heading : kind == 'L' ? s.left : s.up;
      return;
    }
    try {
      turtle_.execute(command, args, geometry_);
    } catch (const SurfaceError&) {
      // No surfaces here; placing one does not move the turtle.
    }
  }

  Turtle turtle_;
  Geometry geometry_;
  uint64_t cell_ = 0;
  std::unordered_map<uint64_t, glm::dvec3> noted_;
};

}  // namespace

TurtleDef turtleDefOf(const InterpretSettings& settings) {
  TurtleDef def;
  def.step = settings.step;
  def.angle = settings.angle;
  def.yawAngle = settings.yawAngle;
  def.radius = settings.radius;
  def.radians = settings.radians;
  return def;
}

std::shared_ptr<const TurtleQueries> TurtleQueries::forSettings(const InterpretSettings& settings) {
  return std::make_shared<const TurtleQueries>(turtleDefOf(settings));
}

void TurtleQueries::respond(const World& world, std::vector<QueryAnswer>& answers) const {
  QueryingTurtle turtle(def_);
  turtle.beginFrame({});
  interpretWord(world, turtle);
  const Program& program = world.program();
  for (CellCursor cell = world.rootPool().cursor(); !cell.done(); cell.next()) {
    if (program.masters[cell.master()].query == 0) continue;
    auto it = turtle.noted().find(cell.id());
    if (it == turtle.noted().end()) continue;
    answers.push_back({static_cast<uint32_t>(cell.index()), {it->second.x, it->second.y, it->second.z}});
  }
}

}  // namespace ontogen
