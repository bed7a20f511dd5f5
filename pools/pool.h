#pragma once
// A pool is the neighbourhood structure cells live in (paper 002, section 2.1). Pools are
// polymorphic: the engine makes one virtual call per pool and step, never per cell. Each
// kind interprets context its own way: the linear pool as left/right neighbours in a
// bracketed string; the grid pool (N-D, von Neumann or Moore) and the spatial pool
// (Euclidean distance) follow the same interface.

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <span>
#include <string_view>
#include <vector>

#include "pools/cell_cursor.h"
#include "pools/cell_record.h"
#include "pools/id_replay.h"
#include "pools/large_page_allocator.h"

namespace ontogen {

/// A linear pool's compact word (docs/COMPACT_WORDS.md) and the replay that gives a word
/// held without ids its ids again. Only LinearPool holds one; the base Pool reads it
/// through a pointer that only the linear pool sets, so no other kind of pool can hold a
/// compact word. Mutable: a word held without ids is replaced by the same word with ids
/// when first read (Pool::restoreIds), which readers see as a const pool.
struct CompactHolding {
  mutable CompactWord word;
  // The replay of a word held without ids; `pending` while it has not run. A copy shares
  // the replay and has a lock of its own.
  struct IdsToRestore {
    std::shared_ptr<const IdReplay> replay;
    std::atomic<bool> pending{false};
    std::unique_ptr<std::mutex> lock = std::make_unique<std::mutex>();
    IdsToRestore() = default;
    IdsToRestore(const IdsToRestore& other) : replay(other.replay), pending(other.pending.load()) {}
    IdsToRestore& operator=(const IdsToRestore& other) {
      replay = other.replay;
      pending.store(other.pending.load());
      return *this;
    }
  };
  mutable IdsToRestore ids;
};

/// The arrays a pool keeps its cells and their state in.
using CellArray = std::vector<CellRecord, LargePageAllocator<CellRecord>>;
using StateArray = std::vector<double, LargePageAllocator<double>>;

enum class PoolKind { Linear, Grid, Spatial };

std::string_view poolKindName(PoolKind kind);

class Pool {
 public:
  virtual ~Pool() = default;

  virtual PoolKind kind() const = 0;
  /// Dimensions a context relation must have to make sense in this pool (linear: 1).
  virtual int contextDimension() const = 0;
  /// A deep copy (worlds are cheap to copy for evolution and sweeps).
  virtual std::unique_ptr<Pool> clone() const = 0;

  /// A cursor at the first cell, walking them in pool order (the order interpretation
  /// walks them). Readers outside pools/ and core/ read cells this way or with cellAt(),
  /// never through the records (pools/cell_cursor.h).
  CellCursor cursor() const { return cursor(0); }
  /// A cursor at cell `first` (at most size()), for a pass over a chunk of the cells.
  CellCursor cursor(size_t first) const {
    readable();
    if (compact_) return CellCursor(compact_->word, first);
    if (!counted_) return CellCursor(cells_, state_.data(), first);
    return CellCursor(cells_, state_.data(), first, anyState_ ? stateCounts_.data() : nullptr,
                      first < cells_.size() ? stateOffset(first) : state_.size());
  }
  /// Cell i (below size()).
  CellView cellAt(size_t i) const {
    readable();
    if (compact_) return compact_->word.cellAt(i);
    const CellRecord& cell = cells_[i];
    return {cell.master, state_.data() + stateOffset(i), cell.birth, cell.id, i};
  }
  /// Where cell i's values start in stateArena() (and in any array laid out like it, as
  /// an integrator's stages are). In a pool that counts its values (countValues), the
  /// offset of its block of kStateBlock cells plus the values of the cells before it in
  /// the block.
  size_t stateOffset(size_t i) const {
    if (compact_) return compact_->word.locate(i).value;
    if (!counted_) return cells_[i].state;
    if (!anyState_) return 0;
    const size_t block = i / kStateBlock;
    size_t offset = blockOffsets_[block];
    for (size_t j = block * kStateBlock; j < i; ++j) offset += stateCounts_[cells_[j].master];
    return offset;
  }

  /// The same, walking from cell `from` (whose values start at `offset`) when it is
  /// nearer to i than the start of i's block: a neighbour of a cell a cursor is on.
  size_t stateOffsetNear(size_t i, size_t from, size_t offset) const {
    if (compact_) return stateOffset(i);
    if (!counted_) return cells_[i].state;
    if (i >= from && i - from < i % kStateBlock) {
      for (size_t j = from; j < i; ++j) offset += stateCounts_[cells_[j].master];
      return offset;
    }
    if (i < from && from - i < kStateBlock) {
      for (size_t j = i; j < from; ++j) offset -= stateCounts_[cells_[j].master];
      return offset;
    }
    return stateOffset(i);
  }

  /// From now on, readers find each cell's values by the number of values of each master
  /// (`perMaster`, indexed by master) rather than by the offset in its record: a running
  /// sum in cursors, a per-block offset for cellAt and stateOffset. The linear pool's
  /// words keep their values in word order, so the record's offset is redundant there
  /// (docs/COMPACT_WORDS.md, slice 3). Cells must keep their values in pool order.
  void countValues(std::vector<uint32_t> perMaster);
  /// Whether countValues was called: random access to values costs a walk in a block.
  bool countsValues() const { return counted_; }
  /// Cells per entry of the block offsets: one 32-bit offset per 64 cells, and at most 63
  /// masters' counts added to reach a cell.
  static constexpr size_t kStateBlock = 64;

  /// The records themselves, in pool order: for pools/ and core/ only, which write and
  /// scan them where a pool keeps records. A linear pool holding a compact word has none
  /// (holdsCompactWord): asking for them then is an internal error.
  /// In a pool that counts its values, the records' `state` is not read.
  std::span<const CellRecord> cells() const {
    if (compact_) [[unlikely]]
      noRecords();
    return cells_;
  }
  std::span<CellRecord> cells() {
    if (compact_) [[unlikely]]
      noRecords();
    return cells_;
  }
  size_t size() const { return compact_ ? compact_->word.size() : cells_.size(); }
  /// The state values of a cell (count given by its master).
  const double* stateOf(const CellRecord& cell) const { return state_.data() + cell.state; }
  double* stateOf(const CellRecord& cell) { return state_.data() + cell.state; }
  std::span<const double> stateArena() const {
    return compact_ ? std::span<const double>(compact_->word.values()) : std::span<const double>(state_);
  }
  /// The state values themselves, for an integrator that advances them in place (a pool
  /// of records).
  StateArray& stateValues() {
    if (compact_) [[unlikely]]
      noRecords();
    return state_;
  }

  /// Bytes in use, for the memory limit. Capacity reserved beyond the size is not
  /// counted: pages never written are never mapped.
  size_t bytes() const {
    if (!compact_) return cells_.size() * sizeof(CellRecord) + state_.size() * sizeof(double);
    return compact_->word.bytes() + (compact_->ids.replay ? compact_->ids.replay->bytes() : 0);
  }

  /// Whether the cells are held as a compact word (docs/COMPACT_WORDS.md) rather than as
  /// records: a linear pool whose development rewrites its words in that form.
  bool holdsCompactWord() const { return compact_ != nullptr; }
  /// The compact word, as the development holds it: perhaps without ids (holdsIds()).
  /// Only while holdsCompactWord().
  const CompactWord& compactWord() const { return compact_->word; }

  /// Whether the compact word holds its ids. A word held without them (CompactWord::
  /// holdsIds, docs/COMPACT_WORDS.md "Words without ids") is given its ids again by its
  /// replay, once, the first time a reader asks for a cell (cursor, cellAt) or the
  /// records: thread-safe, and invisible to readers but for the time it takes.
  bool holdsIds() const { return !compact_ || !compact_->ids.pending.load(std::memory_order_acquire); }
  /// Gives a word held without ids its ids now (as the first reader would).
  void ensureIds() const { readable(); }
  /// The replay of a word held without ids, or null.
  std::shared_ptr<const IdReplay> idReplay() const { return holdsIds() ? nullptr : compact_->ids.replay; }

  /// Changes whenever cells are added, removed or reordered (not when state values
  /// change), so a caller can keep what it derived from the structure until then.
  uint64_t structureVersion() const { return version_; }

  /// Appends a cell with `count` state values copied from `values` (a pool of records).
  void append(CellRecord cell, const double* values, uint32_t count);
  /// Replaces the contents with another pool's (same kind), reusing storage.
  void swapContents(CellArray& cells, StateArray& state);
  void reserve(size_t cells, size_t values);
  void clear();

 protected:
  /// The block offsets of the cells as they are now (countValues).
  void indexValues();
  [[noreturn]] static void noRecords();
  /// Back to records: the linear pool forgets its compact word and its storage (called
  /// only while holdsCompactWord(), which only a linear pool can).
  virtual void dropCompactWord() {}
  /// Before a reader sees the cells: a word held without ids is given them.
  void readable() const {
    if (compact_ && compact_->ids.pending.load(std::memory_order_acquire)) [[unlikely]]
      restoreIds();
  }
  void restoreIds() const;

  CellArray cells_;
  StateArray state_;
  uint64_t version_ = 0;
  bool counted_ = false;                // countValues was called
  bool anyState_ = false;               // some master has values
  std::vector<uint32_t> stateCounts_;   // values per master
  std::vector<uint32_t> blockOffsets_;  // where each block's first cell's values start

 private:
  friend class LinearPool;  // the one kind of pool that holds a compact word
  // The linear pool's compact word while the cells are held so, not in cells_ and state_;
  // null otherwise, and always in a grid or spatial pool.
  const CompactHolding* compact_ = nullptr;
};

}  // namespace ontogen
