#pragma once
// A module as a writer hands it to a pool: its master, its birth and the coordinates of
// its id, (key, k), rather than the id itself. Every new cell's id is mixKey(key, k): the
// successors of one event share the key (their lineage) and differ only in k, their
// number in the rule (core/successors.h). A compact word (docs/COMPACT_WORDS.md) stores a
// run of such modules as one key and a first k, so the writer must hand over the pair;
// whoever needs the id derives it with id().
//
// A module whose id is not known by its coordinates (a cell read back from records, an
// axiom cell, the homomorphism's salted cells) carries the id itself as its key, with
// k = kOwnId. `me` and `=X` copy the coordinates of the cell they come from, so they keep
// its id either way.

#include <cstdint>

#include "model/random.h"
#include "pools/cell_cursor.h"
#include "pools/cell_record.h"

namespace ontogen {

struct ModuleValue {
  /// k of a module whose key is its id. Successor numbers count from 1 and a rule has
  /// far fewer than 2^32 - 1 successors, so no successor has this k.
  static constexpr uint32_t kOwnId = UINT32_MAX;

  uint32_t master = 0;  ///< index of the master cell in the program
  uint32_t k = kOwnId;  ///< number of the module among its event's successors, from 1
  double birth = 0;     ///< global time at which the module had age 0 (seconds)
  uint64_t key = 0;     ///< the event's lineage key, or the id itself when k is kOwnId

  /// The stable id (64 bits): mixKey(key, k), or the key when k is kOwnId.
  uint64_t id() const { return k == kOwnId ? key : mixKey(key, k); }
};

/// The module a stored record holds (its id as its key).
inline ModuleValue moduleOf(const CellRecord& cell) { return {cell.master, ModuleValue::kOwnId, cell.birth, cell.id}; }

/// The module of a cell as a cursor gives it (its id as its key).
inline ModuleValue moduleOf(const CellView& cell) { return {cell.master, ModuleValue::kOwnId, cell.birth, cell.id}; }

/// The record a pool stores for `module`; its `state` offset is left for the pool to set.
inline CellRecord recordOf(const ModuleValue& module) { return {module.master, 0, module.birth, module.id()}; }

}  // namespace ontogen
