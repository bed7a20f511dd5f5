#include "core/word.h"


#include "core/parents.h"

namespace ontogen {

std::vector<WordCell> captureWord(const World& world) {
  std::vector<WordCell> word;
  const Program& program = world.program();
  const Pool& pool = world.rootPool();
  word.reserve(pool.size());
  const bool grid = world.rootSystem().poolKind == PoolKind::Grid;
  const bool spatial = world.rootSystem().poolKind == PoolKind::Spatial;
  const int dimensions = spatial ? 3 : world.rootSystem().grid.dimensions;
  const auto cells = pool.cells();
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  const bool linear = world.rootSystem().poolKind == PoolKind::Linear;
  AxialWalk walk(above);
  for (size_t i = 0; i < cells.size(); ++i) {
    const CellRecord& cell = cells[i];
    const MasterCell& master = program.masters[cell.master];
    WordCell entry;
    if (grid || spatial) {
      const auto position = world.positionOf(i);
      entry.position.assign(position.begin(), position.begin() + dimensions);
    }
    entry.label = master.label;
    const double* state = pool.stateOf(cell);
    entry.params.assign(state, state + master.stateCount());
    world.developedValues(cell, entry.developed);
    entry.age = world.ageOf(cell);
    entry.timed = master.timedNotation;
    entry.id = cell.id;
    entry.parent = linear ? walk.next(cell, master) : above;
    entry.system = master.system >= 0;
    if (const World* child = world.childOf(cell)) entry.pool = captureWord(*child);
    word.push_back(std::move(entry));
  }
  return word;
}

}  // namespace ontogen
