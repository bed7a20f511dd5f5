#pragma once
// The spatial pool (paper 002, section 2.1): cells in creation order, each at the
// position its state gives (the variables named x, y and z; a missing one is 0), and
// neighbours within a Euclidean radius. Neighbours are found through a hashed grid of
// buckets one radius wide: a query looks at the 27 buckets around a cell, so it costs
// the same at a thousand cells and at a million as long as the density holds. A k-d
// tree (nanoflann) would cost O(n log n) to rebuild every step as cells move, and the
// fixed radius is exactly what a bucket grid is made for.

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
  /// Replaces `out` with the cells within the radius of cell i, other than i, in a
  /// fixed order (bucket by bucket, then pool order). Needs index().
  void neighbours(size_t i, std::vector<uint32_t>& out) const;

 private:
  static uint64_t bucketKey(int64_t x, int64_t y, int64_t z);
  std::array<int64_t, 3> bucketOf(const std::array<double, 3>& p) const;

  double radius_;
  std::vector<std::array<int, 3>> slots_;
  std::vector<uint32_t> order_;  ///< cell indices sorted by bucket, then index
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> buckets_;  ///< key -> range of order_
};

}  // namespace ontogen
