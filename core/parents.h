#pragma once
// Who hangs from whom: each cell's parent in its world's structure, by stable id.
//
// In a linear pool the word is ABOP's axial tree: a module hangs from the nearest node
// before it on its path to the root, a branch `[ ... ]` from the node before its `[`.
// Nodes are the modules whose label is a name (F, A, cC, joint ...); brackets and the
// punctuation symbols (+ - & ^ \ / | $ ! and the others of section 2) turn or set the
// turtle and are not nodes, so in `F(1) [ + F(2) ] F(3)` both F(2) and F(3) (and the
// `+`) hang from F(1). An unbracketed filament is a chain: each cell hangs from its left
// neighbour. The first nodes of a nested pool hang from their system cell; in the root
// pool they have no parent. In grid and spatial pools every cell hangs from its system
// cell (none in the root pool): their neighbourhoods are not a tree.

#include <array>
#include <cstdint>
#include <vector>

#include "core/world.h"

namespace ontogen {

/// Marks "no parent" among parent ids.
inline constexpr uint64_t kNoParent = ~uint64_t{0};

/// For each cell of the world's pool (in pool order), the index of the cell it hangs
/// from in the same pool, or -1 when it hangs from the pool's system cell (or nothing).
std::vector<int64_t> parentIndices(const World& world);
/// The same for the cells of a linear pool, from `cells` (at its first) to the end, into
/// `out`.
void axialParents(CellCursor cells, const std::vector<MasterCell>& masters, std::vector<int64_t>& out);

/// For each cell of the world's pool, its parent's stable id, or kNoParent.
std::vector<uint64_t> parentIds(const World& world);

/// Whether a master is a node of the axial tree (a module named by a name; the compiler
/// decides, MasterCell::treeNode).
inline bool isTreeNode(const MasterCell& master) { return master.treeNode; }

/// Walks a linear pool's cells in order and gives each its parent's id, without
/// allocating for words whose branches nest less than 32 deep.
class AxialWalk {
 public:
  /// `above`: what the pool's first cells hang from (the system cell, or kNoParent).
  explicit AxialWalk(uint64_t above) : current_(above) {}
  /// The parent id of the next cell, in pool order: the one under `cell`, whose id is
  /// read only for nodes of the tree.
  uint64_t next(const CellCursor& cell, const MasterCell& master) {
    const uint64_t parent = current_;
    if (master.symbolClass & kSymbolBranchOpen) {
      push(current_);
    } else if (master.symbolClass & kSymbolBranchClose) {
      if (depth_ > 0) current_ = pop();  // an unbalanced `]` closes nothing
      return current_;
    } else if (isTreeNode(master)) {
      current_ = cell.id();
    }
    return parent;
  }

 private:
  static constexpr size_t kInline = 32;
  void push(uint64_t id) {
    if (depth_ < kInline)
      inline_[depth_] = id;
    else
      deeper_.push_back(id);
    ++depth_;
  }
  uint64_t pop() {
    --depth_;
    if (depth_ < kInline) return inline_[depth_];
    const uint64_t id = deeper_.back();
    deeper_.pop_back();
    return id;
  }
  uint64_t current_;
  size_t depth_ = 0;
  std::array<uint64_t, kInline> inline_;  // left unset: only what push() wrote is read
  std::vector<uint64_t> deeper_;
};

}  // namespace ontogen
