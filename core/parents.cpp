#include "core/parents.h"


namespace ontogen {


void axialParents(std::span<const CellRecord> cells, const std::vector<MasterCell>& masters,
                  std::vector<int64_t>& parents) {
  parents.assign(cells.size(), -1);
  int64_t current = -1;          // the node the next module hangs from
  std::vector<int64_t> branches;  // `current` where each open branch began
  for (size_t i = 0; i < cells.size(); ++i) {
    const MasterCell& master = masters[cells[i].master];
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
    axialParents(world.rootPool().cells(), world.program().masters, parents);
  return parents;
}

std::vector<uint64_t> parentIds(const World& world) {
  const auto cells = world.rootPool().cells();
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  std::vector<uint64_t> ids(cells.size(), above);
  if (world.rootSystem().poolKind != PoolKind::Linear) return ids;
  const auto& masters = world.program().masters;
  AxialWalk walk(above);
  for (size_t i = 0; i < cells.size(); ++i) ids[i] = walk.next(cells[i], masters[cells[i].master]);
  return ids;
}

}  // namespace ontogen
