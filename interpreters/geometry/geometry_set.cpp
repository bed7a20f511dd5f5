#include "interpreters/geometry/geometry_set.h"

#include "interpreters/geometry/turtle_commands.h"

#include <algorithm>
#include <new>
#include <stdexcept>

namespace ontogen {

namespace {
// The most nodes (2.8 GB of address space) and lines (0.9 GB) expectCells reserves,
// touched only as written.
constexpr std::size_t kMaxReservedNodes = std::size_t{1} << 24;
}  // namespace

GeometrySet::GeometrySet(const GeometrySetDef& def)
    : def_(def),
      recordsNodes_(def.sceneNodes || def.output.writeGlb),
      output_(def.output),
      turtle_(def.turtle),
      scene_{0, Geometry(def.mesh), {}, {}} {}

bool GeometrySet::knows(std::string_view command) const {
  return findTurtleCommand(command) != nullptr;
}

void GeometrySet::beginFrame(const FrameTarget& target) {
  target_ = target;
  turtle_.reset();
  scene_.geometry.clear();
  scene_.nodes.clear();
  scene_.time = target.time;
  hasPending_ = false;
}

// Each cell that draws becomes a node: where the turtle stood as it began, and the
// stretch of the geometry it drew until the next cell began. Most cells of a word draw
// nothing (turns, brackets), so a cell is only noted as it begins, and becomes a node
// when the next one begins if it drew.
void GeometrySet::beginCell(const CellContext& cell) {
  if (!recordsNodes_) return;
  closeNode();
  const TurtleState& state = turtle_.state();
  pending_.id = cell.id;
  pending_.parent = cell.parent;
  pending_.label = cell.label;
  pending_.birth = cell.birth;
  pending_.position = state.position;
  pending_.orientation = glm::dmat3(state.heading, state.left, state.up);
  pending_.range.firstTriangle = static_cast<uint32_t>(scene_.geometry.triangleCount());
  pending_.range.firstSegment = static_cast<uint32_t>(scene_.geometry.segmentCount());
  hasPending_ = true;
}

void GeometrySet::closeNode() {
  if (!hasPending_) return;
  hasPending_ = false;
  GeometryRange& range = pending_.range;
  range.triangleCount = static_cast<uint32_t>(scene_.geometry.triangleCount()) - range.firstTriangle;
  range.segmentCount = static_cast<uint32_t>(scene_.geometry.segmentCount()) - range.firstSegment;
  if (!range.empty()) scene_.nodes.push_back(pending_);
}

void GeometrySet::execute(std::string_view command, std::span<const double> args) {
  if (const TurtleCommand* found = findTurtleCommand(command)) run(*found, args);
}

void GeometrySet::executeCommand(int id, std::string_view command, std::span<const double> args) {
  const auto table = turtleCommands();
  if (id >= 0 && static_cast<size_t>(id) < table.size())
    run(table[id], args);
  else
    execute(command, args);
}

void GeometrySet::run(const TurtleCommand& command, std::span<const double> args) {
  const TurtleWarnings before = turtle_.warnings();
  const uint64_t dropped = scene_.geometry.dropped();
  try {
    turtle_.execute(command, args, scene_.geometry);
  } catch (const SurfaceError& surface) {
    refuse(surface.what());  // an undefined surface, a bad blend: at the instruction that names it
  } catch (const std::length_error& full) {
    refuse(full.what());  // the frame's mesh is full
  }
  const TurtleWarnings& after = turtle_.warnings();
  unmatchedPops_.add(static_cast<uint64_t>(after.unmatchedPops - before.unmatchedPops), site_);
  badArguments_.add(static_cast<uint64_t>(after.badArguments - before.badArguments), site_);
  notDrawn_.add(scene_.geometry.dropped() - dropped, site_);
}

std::vector<SetWarning> GeometrySet::takeWarnings() {
  std::vector<SetWarning> out;
  unmatchedPops_.takeInto(out, "the turtle ignored " + std::to_string(unmatchedPops_.count) +
                                   " unmatched ']' (the first here)");
  badArguments_.takeInto(out, "the turtle ignored " + std::to_string(badArguments_.count) +
                                  " commands with bad arguments: a wrong count, or values not finite or out of range "
                                  "(the first here)");
  notDrawn_.takeInto(out, "the turtle left out " + std::to_string(notDrawn_.count) +
                              " shapes with coordinates not finite or beyond ±1e30 model units, which no output can "
                              "hold (the first here)");
  // And what its own output stage left out, when the set writes its frames itself.
  for (SetWarning& warning : output_.takeWarnings()) out.push_back(std::move(warning));
  return out;
}

void GeometrySet::finishScene() {
  closeNode();
  // What the turtle meshes at the end (open generalized cylinders, plates) belongs to
  // the frame, not to the last cell.
  const uint64_t dropped = scene_.geometry.dropped();
  turtle_.finish(scene_.geometry);
  notDrawn_.add(scene_.geometry.dropped() - dropped, site_);
}

void GeometrySet::expectCells(std::size_t cells) {
  // A line per cell: each F of a plant draws one, so a million lines are written once into
  // room taken at once instead of copied about twenty times into ever fresh pages; the
  // pages of cells that draw no line (turns, brackets) are never touched.
  try {
    scene_.geometry.reserveSegments(std::min<std::size_t>(cells, kMaxReservedNodes));
  } catch (const std::bad_alloc&) {
  }
  if (!recordsNodes_ || cells <= scene_.nodes.capacity()) return;
  // Reserved once, not grown by doubling: a plant's million nodes would otherwise be
  // moved about twenty times into ever fresh pages. Only the nodes written are touched;
  // an address space that refuses the reservation grows them as before.
  try {
    scene_.nodes.reserve(std::min<std::size_t>(cells, kMaxReservedNodes));
  } catch (const std::bad_alloc&) {
  }
}

void GeometrySet::contribute(Scene& scene) {
  finishScene();
  scene.time = scene_.time;
  scene.append(std::move(scene_));
  scene_.clear();
}

std::vector<std::filesystem::path> GeometrySet::endFrame() {
  finishScene();
  return output_.write(scene_, target_);
}

}  // namespace ontogen
