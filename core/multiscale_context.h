#pragma once
// An L-system rule's context in a multiscale word (L-Py's multiscale modules, its string
// matching "As Multiscale AxialTree"; docs/LANGUAGE.md 4.8). A `scale N:` line gives
// labels a scale; a smaller number is a coarser scale (a plant 0, its axes 1, their
// internodes 2), and a module without one is finer than all. Each pattern module is
// looked for at its own scale:
//  - on the left, and in a new left context `<<` among what the step has written before
//    the module, among the module's ancestors on the path towards the root (branches
//    passed over, `[` left behind, as in the ordinary matching), past the modules finer
//    than the pattern's scale, and past the complexes of the module when the pattern is
//    not coarser than it;
//  - on the right, along the word: the modules finer than the pattern's scale are passed
//    over, branches' brackets among them; a coarser module is entered through its
//    components. A pattern's `[` and `]` (which have no scale) enter a branch and leave
//    the rest of it as in the ordinary matching.
// Ignored symbols are passed over on both sides. With levels (`level N:` lines, L-Py's
// multi-level matching, whose levels are not ordered) a pattern module is the nearest
// ancestor, or the next module along the word, of its level, every other passed over.

#include <cstdint>
#include <span>

#include "model/program.h"
#include "pools/linear_pool.h"

namespace ontogen {

/// Matches `rule`'s left and right contexts around cell `index` of `pool` (whose branches
/// are indexed) with the rule's scales (CompiledRule::scales), seeing `classOf`; on
/// success matched[k] is the cell of items[k] of the side last matched, as
/// LinearPool::matchLeft and matchRight give them.
bool matchMultiscaleLeft(const LinearPool& pool, size_t index, std::span<const ContextItem> items,
                         std::span<const uint8_t> classOf, const ScaleTable& scales, uint32_t* matched);
/// Matches a new left context `<<`, nearest first, against `written`, the word a forward
/// pass has written so far, for a module of `master` written next (whose scale the walk
/// starts from, as L-Py reads it); matched[k] indexes `written`.
bool matchMultiscaleNewLeft(std::span<const CellRecord> written, uint32_t master, std::span<const ContextItem> items,
                            std::span<const uint8_t> classOf, const ScaleTable& scales, uint32_t* matched);
bool matchMultiscaleRight(const LinearPool& pool, size_t index, std::span<const ContextItem> items,
                          std::span<const uint8_t> classOf, const ScaleTable& scales, uint32_t* matched);

}  // namespace ontogen
