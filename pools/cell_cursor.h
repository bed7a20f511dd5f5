#pragma once
// Reading a pool's cells without seeing how the pool stores them. A CellCursor walks the
// cells in pool order and gives each one's master (its label), state values, birth time,
// id and index; Pool::cellAt(i) gives the same for one cell, as a CellView. Readers
// outside pools/ and core/ (interpreters/, apps/, bench/) read cells only this way, so a
// pool can change how it stores them (docs/COMPACT_WORDS.md: the linear pool's compact
// words) without touching those readers. Grid and spatial pools keep 24-byte records
// (pools/cell_record.h); a linear pool keeps records or a compact word
// (pools/compact_word.h), and the cursor walks either.
//
// The cursor answers with accessors rather than a record so that a value a store derives
// (the id of a compact word is a hash of its run's key) is computed only when asked.

#include <cstddef>
#include <cstdint>
#include <span>

#include "pools/cell_record.h"
#include "pools/cell_view.h"
#include "pools/compact_word.h"

namespace ontogen {

/// Walks cells in pool order:
/// `for (CellCursor cell = pool.cursor(); !cell.done(); cell.next()) use(cell.master());`
/// It borrows the storage it walks and is invalid once that changes.
class CellCursor {
 public:
  /// A cursor at cell `first` of `cells` (done() when it is past the last), whose state
  /// offsets index `state`.
  CellCursor(std::span<const CellRecord> cells, const double* state, size_t first = 0)
      : cells_(cells), state_(state), index_(first) {}
  /// A cursor that does not read the records' state offsets: it keeps a running sum of
  /// the values of the cells it passes, `counts[master]` each (null: none has values),
  /// from `offset`, where cell `first`'s values start.
  CellCursor(std::span<const CellRecord> cells, const double* state, size_t first, const uint32_t* counts,
             size_t offset)
      : cells_(cells), state_(state), index_(first), counts_(counts), offset_(offset), summed_(true) {}
  /// A cursor at module `first` of a compact word.
  explicit CellCursor(const CompactWord& word, size_t first = 0)
      : state_(nullptr), compact_(true), words_(word, first) {}

  /// Whether the cursor has passed the last cell.
  bool done() const { return compact_ ? words_.done() : index_ >= cells_.size(); }
  /// Moves to the next cell in pool order.
  void next() {
    if (compact_) return words_.next();
    if (counts_) offset_ += counts_[cells_[index_].master];
    ++index_;
  }
  /// Cells the cursor walks, in all.
  size_t size() const { return compact_ ? words_.size() : cells_.size(); }

  // The cell under the cursor (not done()).
  size_t index() const { return compact_ ? words_.index() : index_; }
  uint32_t master() const { return compact_ ? words_.master() : cells_[index_].master; }
  const double* state() const { return compact_ ? words_.state() : state_ + stateOffset(); }
  double birth() const { return compact_ ? words_.birth() : cells_[index_].birth; }
  uint64_t id() const { return compact_ ? words_.id() : cells_[index_].id; }
  /// Where the cell's values start in the state array (and in any array laid out like
  /// it, as an integrator's stages are).
  size_t stateOffset() const {
    if (compact_) return words_.stateOffset();
    return summed_ ? offset_ : cells_[index_].state;
  }
  CellView view() const { return {master(), state(), birth(), id(), index()}; }

 private:
  std::span<const CellRecord> cells_;
  const double* state_;
  size_t index_ = 0;
  const uint32_t* counts_ = nullptr;
  size_t offset_ = 0;
  bool summed_ = false;
  bool compact_ = false;  // walks words_ instead of cells_
  CompactWordCursor words_;
};

}  // namespace ontogen
