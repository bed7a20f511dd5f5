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

#include <cstdint>
#include <vector>

#include "core/world.h"

namespace ontogen {

/// Marks "no parent" among parent ids.
inline constexpr uint64_t kNoParent = ~uint64_t{0};

/// For each cell of the world's pool (in pool order), the index of the cell it hangs
/// from in the same pool, or -1 when it hangs from the pool's system cell (or nothing).
std::vector<int64_t> parentIndices(const World& world);

/// For each cell of the world's pool, its parent's stable id, or kNoParent.
std::vector<uint64_t> parentIds(const World& world);

/// Whether a master is a node of the axial tree (a module named by a name).
bool isTreeNode(const MasterCell& master);

}  // namespace ontogen
