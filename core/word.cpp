#include "core/word.h"

#include <array>

#include "core/homomorphism.h"
#include "core/parents.h"

namespace ontogen {

namespace {

// Streams the word under `cell` (the pool's, or a homomorphism's image whose i-th cell
// comes from the pool's cell sourceOf(i)).
template <typename SourceOf>
void stream(const World& world, CellCursor cell, SourceOf&& sourceOf, bool interpreted, WordVisitor& visitor) {
  const Program& program = world.program();
  const bool grid = world.rootSystem().poolKind == PoolKind::Grid;
  const bool spatial = world.rootSystem().poolKind == PoolKind::Spatial;
  const int dimensions = spatial ? 3 : world.rootSystem().grid.dimensions;
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  const bool linear = world.rootSystem().poolKind == PoolKind::Linear;
  AxialWalk walk(above);
  std::vector<double> developed;
  std::array<double, 3> position{};
  // One view, refilled for each cell (a fresh one per cell costs more than the cell).
  WordCellView view;
  for (; !cell.done(); cell.next()) {
    const MasterCell& master = program.masters[cell.master()];
    if (grid || spatial) {
      position = world.positionOf(sourceOf(cell.index()));
      view.position = std::span<const double>(position.data(), static_cast<size_t>(dimensions));
    }
    view.label = master.label;
    const double* state = cell.state();
    const size_t count = master.stateCount();
    view.params = std::span<const double>(state, count);
    if (master.developmentFunction < 0) {
      view.developed = std::span<const double>(state, count);
    } else {
      world.developedValues(cell.view(), developed);
      view.developed = developed;
    }
    view.age = world.time() - cell.birth();
    view.timed = master.timedNotation;
    view.id = cell.id();
    view.parent = linear ? walk.next(cell, master) : above;
    view.system = master.system >= 0;
    visitor.cell(view);
    if (!view.system) continue;
    visitor.enterPool();
    if (const World* child = world.childOf(view.id)) {
      if (interpreted)
        visitInterpretedWord(*child, visitor);
      else
        visitWord(*child, visitor);
    }
    visitor.leavePool();
  }
}

// Collects a streamed word into records, nested pools into their system cells.
class WordCollector final : public WordVisitor {
 public:
  void cell(const WordCellView& view) override {
    WordCell entry;
    entry.label = view.label;
    entry.params.assign(view.params.begin(), view.params.end());
    entry.developed.assign(view.developed.begin(), view.developed.end());
    entry.age = view.age;
    entry.timed = view.timed;
    entry.id = view.id;
    entry.parent = view.parent;
    entry.position.assign(view.position.begin(), view.position.end());
    entry.system = view.system;
    current().push_back(std::move(entry));
  }
  void enterPool() override { open_.push_back(&current().back().pool); }
  void leavePool() override { open_.pop_back(); }
  std::vector<WordCell> take() { return std::move(word_); }

 private:
  std::vector<WordCell>& current() { return open_.empty() ? word_ : *open_.back(); }
  std::vector<WordCell> word_;
  std::vector<std::vector<WordCell>*> open_;  // the pools being filled, innermost last
};

}  // namespace

void visitWord(const World& world, WordVisitor& visitor) {
  stream(world, world.rootPool().cursor(), [](size_t i) { return i; }, false, visitor);
}

void visitInterpretedWord(const World& world, WordVisitor& visitor) {
  if (!world.rootSystem().homomorphism) {
    stream(world, world.rootPool().cursor(), [](size_t i) { return i; }, true, visitor);
    return;
  }
  const HomomorphismImage image(world);
  stream(world, image.cursor(), [&image](size_t i) { return image.sourceOf(i); }, true, visitor);
}

void visitWord(const std::vector<WordCell>& word, WordVisitor& visitor) {
  for (const WordCell& cell : word) {
    WordCellView view;
    view.label = cell.label;
    view.params = cell.params;
    view.developed = cell.developed;
    view.age = cell.age;
    view.timed = cell.timed;
    view.id = cell.id;
    view.parent = cell.parent;
    view.position = cell.position;
    view.system = cell.system;
    visitor.cell(view);
    if (!cell.system) continue;
    visitor.enterPool();
    visitWord(cell.pool, visitor);
    visitor.leavePool();
  }
}

std::vector<WordCell> captureWord(const World& world) {
  WordCollector collector;
  visitWord(world, collector);
  return collector.take();
}

std::vector<WordCell> captureInterpretedWord(const World& world) {
  WordCollector collector;
  visitInterpretedWord(world, collector);
  return collector.take();
}

}  // namespace ontogen
