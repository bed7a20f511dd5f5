#include "core/word.h"

#include "core/homomorphism.h"
#include "core/parents.h"

namespace ontogen {

namespace {

// The word of `cells` (the pool's, or a homomorphism's image whose i-th cell comes from
// the pool's cell sourceOf(i)), with state from `stateOf`.
template <typename StateOf, typename SourceOf>
std::vector<WordCell> capture(const World& world, std::span<const CellRecord> cells, StateOf&& stateOf,
                              SourceOf&& sourceOf, bool interpreted) {
  std::vector<WordCell> word;
  const Program& program = world.program();
  word.reserve(cells.size());
  const bool grid = world.rootSystem().poolKind == PoolKind::Grid;
  const bool spatial = world.rootSystem().poolKind == PoolKind::Spatial;
  const int dimensions = spatial ? 3 : world.rootSystem().grid.dimensions;
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  const bool linear = world.rootSystem().poolKind == PoolKind::Linear;
  AxialWalk walk(above);
  for (size_t i = 0; i < cells.size(); ++i) {
    const CellRecord& cell = cells[i];
    const MasterCell& master = program.masters[cell.master];
    WordCell entry;
    if (grid || spatial) {
      const auto position = world.positionOf(sourceOf(i));
      entry.position.assign(position.begin(), position.begin() + dimensions);
    }
    entry.label = master.label;
    const double* state = stateOf(cell);
    entry.params.assign(state, state + master.stateCount());
    world.developedValues(cell, state, entry.developed);
    entry.age = world.ageOf(cell);
    entry.timed = master.timedNotation;
    entry.id = cell.id;
    entry.parent = linear ? walk.next(cell, master) : above;
    entry.system = master.system >= 0;
    if (const World* child = world.childOf(cell))
      entry.pool = interpreted ? captureInterpretedWord(*child) : captureWord(*child);
    word.push_back(std::move(entry));
  }
  return word;
}

}  // namespace

std::vector<WordCell> captureWord(const World& world) {
  const Pool& pool = world.rootPool();
  return capture(
      world, pool.cells(), [&pool](const CellRecord& cell) { return pool.stateOf(cell); },
      [](size_t i) { return i; }, false);
}

std::vector<WordCell> captureInterpretedWord(const World& world) {
  if (!world.rootSystem().homomorphism) {
    const Pool& pool = world.rootPool();
    return capture(
        world, pool.cells(), [&pool](const CellRecord& cell) { return pool.stateOf(cell); },
        [](size_t i) { return i; }, true);
  }
  const HomomorphismImage image(world);
  return capture(
      world, image.cells(), [&image](const CellRecord& cell) { return image.stateOf(cell); },
      [&image](size_t i) { return image.sourceOf(i); }, true);
}

}  // namespace ontogen
