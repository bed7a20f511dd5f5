#pragma once
// How a pool makes again the ids of a compact word held without them
// (docs/COMPACT_WORDS.md, "Words without ids"). A word rewritten by a table is written
// without ids when nobody reads them while it grows; the development leaves with the
// pool what it takes to derive them again, and the pool does so the first time a reader
// asks for a cell (Pool::cursor, Pool::cellAt).

#include <cstddef>

#include "pools/compact_word.h"

namespace ontogen {

class IdReplay {
 public:
  virtual ~IdReplay() = default;
  /// The word with its ids: module for module the labels and births of the word held
  /// without them, and the ids the development would have given it. `heldBytes`: what
  /// the pool holds meanwhile (the word without ids). A replay that would pass the
  /// world's memory limit throws a LimitError (core/limits.h) before it takes the memory.
  virtual CompactWord replay(size_t heldBytes) const = 0;
  /// Bytes held to replay (counted with the pool's, for the memory limit).
  virtual size_t bytes() const = 0;
};

}  // namespace ontogen
