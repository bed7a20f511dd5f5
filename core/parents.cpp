#include "core/parents.h"

#include <algorithm>

namespace ontogen {


void axialParents(CellCursor cells, const std::vector<MasterCell>& masters, std::vector<int64_t>& parents) {
  parents.assign(cells.size() - std::min(cells.size(), cells.index()), -1);
  int64_t current = -1;          // the node the next module hangs from
  std::vector<int64_t> branches;  // `current` where each open branch began
  for (size_t i = 0; !cells.done(); ++i, cells.next()) {
    const MasterCell& master = masters[cells.master()];
    parents[i] = current;
    if (master.symbolClass & kSymbolBranchOpen) {
      branches.push_back(current);
    } else if (master.symbolClass & kSymbolBranchClose) {
      if (!branches.empty()) {  // an unbalanced `]` closes nothing
        current = branches.back();
        branches.pop_back();
      }
      parents[i] = current;
    } else if (isTreeNode(master)) {
      current = static_cast<int64_t>(i);
    }
  }
}

std::vector<int64_t> parentIndices(const World& world) {
  std::vector<int64_t> parents(world.rootPool().size(), -1);
  if (world.rootSystem().poolKind == PoolKind::Linear)
    axialParents(world.rootPool().cursor(), world.program().masters, parents);
  return parents;
}

std::vector<uint64_t> parentIds(const World& world) {
  const Pool& pool = world.rootPool();
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  std::vector<uint64_t> ids(pool.size(), above);
  if (world.rootSystem().poolKind != PoolKind::Linear) return ids;
  const auto& masters = world.program().masters;
  AxialWalk walk(above);
  for (CellCursor cell = pool.cursor(); !cell.done(); cell.next())
    ids[cell.index()] = walk.next(cell, masters[cell.master()]);
  return ids;
}

}  // namespace ontogen
