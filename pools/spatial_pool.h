#pragma once
// The spatial pool (paper 002, section 2.1): cells in creation order, each at the
// position its state gives (the variables named x, y and z; a missing one is 0), and
// neighbours within a Euclidean radius. Neighbours are found through a hashed grid of
// buckets one radius wide: a query looks at the 27 buckets around a cell, so it costs
// the same at a thousand cells and at a million as long as the density holds. A k-d
// tree (nanoflann) would cost O(n log n) to rebuild every step as cells move, and the
// fixed radius is exactly what a bucket grid is made for. Where the cells fill their box
// the buckets are a dense array built by counting sort (O(n), no hashing); a sparse
// scatter falls back to a hash of the occupied buckets.

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "pools/pool.h"

namespace ontogen {

class SpatialPool final : public Pool {
 public:
  /// `positionSlots[m]`: for cells of master m, the state indices of x, y, z (-1: 0).
  explicit SpatialPool(double radius = 1, std::vector<std::array<int, 3>> positionSlots = {});

  PoolKind kind() const override { return PoolKind::Spatial; }
  int contextDimension() const override { return 0; }  // no positional context
  std::unique_ptr<Pool> clone() const override { return std::make_unique<SpatialPool>(*this); }

  double radius() const { return radius_; }
  std::array<double, 3> positionOf(size_t i) const;
  /// Rebuilds the buckets from the current positions (a new structure version: the
  /// neighbours may have changed). Call after positions or cells change.
  void index();
  /// Bytes the index holds now: not in bytes(), and for a pool of small cells larger
  /// than the cells themselves; the memory limit counts it.
  size_t indexBytes() const;
  /// At most the bytes index() holds at its peak, a cell: its scratch (24 bytes), order
  /// (4) and positions (24), and the dense buckets with their scratch (36) or the hashed
  /// ones (80 with the table's nodes).
  static constexpr size_t kIndexPeakBytesPerCell = 136;
  /// Replaces `out` with the cells within the radius of cell i, other than i, in a
  /// fixed order (bucket by bucket, then pool order). Needs index().
  void neighbours(size_t i, std::vector<uint32_t>& out) const;
  /// Every cell's neighbours at once, as compressed rows by pool index: cell i's are
  /// cells[offsets[i]] .. cells[offsets[i + 1] - 1], in the order neighbours(i) gives.
  /// The queries go in bucket order, so that neighbouring queries read the same buckets
  /// from the cache (in pool order, a million cells miss it on almost every bucket).
  void neighbourTable(LargeVector<uint32_t>& offsets, LargeVector<uint32_t>& cells) const;

 private:
  static uint64_t bucketKey(int64_t x, int64_t y, int64_t z);
  /// Calls found(k) for each position k of order_ within the radius of `p`, bucket by
  /// bucket, then pool order; `self` (a pool index) is left out.
  template <typename Found>
  void scanAround(const std::array<double, 3>& p, size_t self, Found&& found) const;
  std::array<int64_t, 3> bucketOf(const std::array<double, 3>& p) const;
  /// Index of a bucket in the dense grid, or -1 outside it.
  int64_t denseIndex(int64_t x, int64_t y, int64_t z) const;

  double radius_;
  std::vector<std::array<int, 3>> slots_;
  // The index: cells sorted by bucket (stable: pool order within a bucket), with their
  // positions copied alongside so that a query reads contiguous memory.
  std::vector<uint32_t> order_;
  std::vector<std::array<double, 3>> sorted_;
  mutable LargeVector<uint32_t> flat_;  // neighbourTable's lists in bucket order, kept for reuse
  mutable LargeVector<uint32_t> starts_;
  // Buckets as a dense box over the occupied range when it is not much larger than the
  // number of cells (start offsets into order_), else hashed.
  bool dense_ = true;
  std::array<int64_t, 3> low_{0, 0, 0}, extent_{0, 0, 0};
  std::vector<uint32_t> start_;  ///< dense: per bucket, first position in order_; one more at the end
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> buckets_;  ///< hashed: key -> range of order_
};

}  // namespace ontogen
