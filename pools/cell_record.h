#pragma once
// The compact record a pool keeps for each instance cell. The meaning of `master` and of
// the state values belongs to core; pools only store, order and neighbour them.

#include <cstdint>

namespace ontogen {

/// 24 bytes per cell. The age is not stored: it is `time - birth`, so ages never drift
/// with the step size and a step does not touch cells that do not change.
struct CellRecord {
  uint32_t master = 0;  ///< index of the master cell in the program
  uint32_t state = 0;   ///< offset of the cell's state values in the pool's state arena
  double birth = 0;     ///< global time at which the cell had age 0 (seconds)
  uint64_t id = 0;      ///< stable id, derived from the cell's lineage
};

/// How a master takes part in context matching and branching.
enum SymbolClass : uint8_t {
  kSymbolModule = 0,
  kSymbolBranchOpen = 1,   ///< `[`
  kSymbolBranchClose = 2,  ///< `]`
  kSymbolIgnored = 4,      ///< left out of context matching (`ignore:` / `consider:`)
  kSymbolCut = 8,          ///< `%`: when it expires, it and the rest of its branch are removed
};

}  // namespace ontogen
