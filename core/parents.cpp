#include "core/parents.h"

#include <cctype>

namespace ontogen {

bool isTreeNode(const MasterCell& master) {
  if (master.symbolClass & (kSymbolBranchOpen | kSymbolBranchClose)) return false;
  if (master.label.empty()) return false;
  const unsigned char first = static_cast<unsigned char>(master.label[0]);
  return std::isalpha(first) || first == '_' || first >= 0x80;  // names may be UTF-8 (τ)
}

std::vector<int64_t> parentIndices(const World& world) {
  const Pool& pool = world.rootPool();
  const auto cells = pool.cells();
  std::vector<int64_t> parents(cells.size(), -1);
  if (world.rootSystem().poolKind != PoolKind::Linear) return parents;
  const auto& masters = world.program().masters;
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
  return parents;
}

std::vector<uint64_t> parentIds(const World& world) {
  const std::vector<int64_t> indices = parentIndices(world);
  const auto cells = world.rootPool().cells();
  const uint64_t above = world.parent() ? world.systemCellId() : kNoParent;
  std::vector<uint64_t> ids(indices.size());
  for (size_t i = 0; i < indices.size(); ++i) ids[i] = indices[i] < 0 ? above : cells[indices[i]].id;
  return ids;
}

}  // namespace ontogen
