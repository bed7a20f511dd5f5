#pragma once
// An L-system rule's context in a linear word (docs/LANGUAGE.md 3.7, 4.8): the left and
// right context around a module of the word as it was, and the new left context `<<`
// against the word being written. Productions, decomposition and homomorphism rules all
// match through here, so a wildcard's number of parameters, `∅`, `[` and the names only
// other alternatives bind mean one thing in each.

#include <cstdint>
#include <span>

#include "model/program.h"
#include "pools/linear_pool.h"

namespace ontogen {

/// The word a new context reads: the cells written so far and their state arena. A
/// forward pass writes them in word order (`<<` reads the end); a backward pass writes
/// them right to left, the nearest cell last (`>>` reads from the end).
struct WrittenWord {
  std::span<const CellRecord> cells;
  const double* state = nullptr;
};

/// Matches `rule`'s context around cell `index` of `pool` (whose branches are indexed),
/// its new left or right context against `written`, seeing `classOf`; copies the bound values
/// into `frame` (names of other alternatives read 0). `matched` is scratch space of
/// kMaxContextItems entries.
bool matchLinearContext(const Program& program, const CompiledRule& rule, const LinearPool& pool, size_t index,
                        const WrittenWord& written, std::span<const uint8_t> classOf, double* frame, uint32_t* matched);

}  // namespace ontogen
