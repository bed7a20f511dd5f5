#pragma once
// A pool is the neighbourhood structure cells live in (paper 002, section 2.1). Pools are
// polymorphic: the engine makes one virtual call per pool and step, never per cell. Each
// kind interprets context its own way: the linear pool as left/right neighbours in a
// bracketed string; the grid pool (N-D, von Neumann or Moore) and the spatial pool
// (Euclidean distance) follow the same interface.

#include <cstddef>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "pools/cell_cursor.h"
#include "pools/cell_record.h"
#include "pools/large_page_allocator.h"

namespace ontogen {

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
  CellCursor cursor() const { return CellCursor(cells_, state_.data()); }
  /// A cursor at cell `first`, for a pass over a chunk of the cells.
  CellCursor cursor(size_t first) const { return CellCursor(cells_, state_.data(), first); }
  /// Cell i (below size()).
  CellView cellAt(size_t i) const {
    const CellRecord& cell = cells_[i];
    return {cell.master, stateOf(cell), cell.birth, cell.id, i};
  }
  /// Where cell i's values start in stateArena() (and in any array laid out like it, as
  /// an integrator's stages are).
  size_t stateOffset(size_t i) const { return cells_[i].state; }

  /// The records themselves, in pool order: for pools/ and core/ only, which write and
  /// scan them until the linear pool stores its words compactly (docs/COMPACT_WORDS.md).
  std::span<const CellRecord> cells() const { return cells_; }
  std::span<CellRecord> cells() { return cells_; }
  size_t size() const { return cells_.size(); }
  /// The state values of a cell (count given by its master).
  const double* stateOf(const CellRecord& cell) const { return state_.data() + cell.state; }
  double* stateOf(const CellRecord& cell) { return state_.data() + cell.state; }
  std::span<const double> stateArena() const { return state_; }
  /// The state values themselves, for an integrator that advances them in place.
  StateArray& stateValues() { return state_; }

  /// Bytes in use, for the memory limit. Capacity reserved beyond the size is not
  /// counted: pages never written are never mapped.
  size_t bytes() const { return cells_.size() * sizeof(CellRecord) + state_.size() * sizeof(double); }

  /// Changes whenever cells are added, removed or reordered (not when state values
  /// change), so a caller can keep what it derived from the structure until then.
  uint64_t structureVersion() const { return version_; }

  /// Appends a cell with `count` state values copied from `values`.
  void append(CellRecord cell, const double* values, uint32_t count);
  /// Replaces the contents with another pool's (same kind), reusing storage.
  void swapContents(CellArray& cells, StateArray& state);
  void reserve(size_t cells, size_t values);
  void clear();

 protected:
  CellArray cells_;
  StateArray state_;
  uint64_t version_ = 0;
};

}  // namespace ontogen
