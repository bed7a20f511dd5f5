#pragma once
// What rules read around a cell, for each pool kind: its neighbours (for aggregates),
// its positional context (`A(y) me B(z)`) and its position (`me.x`, `me.y`, `me.z`).
// The development of a pool and the rate integrator see pools only through a view. The
// views share one shape but no base class: the rule evaluator and the integrator are
// templates on the view, so nothing on the per-cell path is a virtual call.
//
// Every view has: pool(); neighbours(i, out), which replaces `out` with the indices of
// the cells next to cell i (empty sites and missing neighbours left out);
// matchContext(rule, i, left, right), which matches a rule's positional context around
// cell i, the matched cells' indices in left[k] and right[k]; and position(i).

#include <array>
#include <cstdint>
#include <vector>

#include "model/program.h"
#include "pools/grid_pool.h"
#include "pools/linear_pool.h"
#include "pools/spatial_pool.h"

namespace ontogen {

/// The linear pool: neighbours are the branch-aware left neighbour (towards the root)
/// and right neighbour (the next module of the same branch), as context sees them.
/// Call LinearPool::indexBranches before using it on a changed word.
class LinearPoolView {
 public:
  LinearPoolView(const LinearPool& pool, std::span<const uint8_t> classOf) : pool_(pool), classOf_(classOf) {}
  const Pool& pool() const { return pool_; }
  void neighbours(size_t i, std::vector<uint32_t>& out) const;
  bool matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const;
  std::array<double, 3> position(size_t i) const { return {static_cast<double>(i), 0, 0}; }

 private:
  const LinearPool& pool_;
  std::span<const uint8_t> classOf_;
};

/// The grid pool: neighbours are the occupied sites of the neighbourhood; a 1-D grid
/// also matches positional context, item k at offset -(k+1) (left) or k+1 (right).
class GridPoolView {
 public:
  explicit GridPoolView(const GridPool& pool) : pool_(pool) {}
  const Pool& pool() const { return pool_; }
  void neighbours(size_t i, std::vector<uint32_t>& out) const;
  bool matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const;
  std::array<double, 3> position(size_t i) const;

 private:
  const GridPool& pool_;
};

/// The spatial pool: neighbours are the cells within its radius (SpatialPool::index
/// must be current); positional context does not apply (the compiler rejects it).
class SpatialPoolView {
 public:
  explicit SpatialPoolView(const SpatialPool& pool) : pool_(pool) {}
  const Pool& pool() const { return pool_; }
  void neighbours(size_t i, std::vector<uint32_t>& out) const { pool_.neighbours(i, out); }
  /// Every cell's neighbours at once, found in bucket order (SpatialPool::neighbourTable).
  void neighbourTable(LargeVector<uint32_t>& offsets, LargeVector<uint32_t>& cells) const {
    pool_.neighbourTable(offsets, cells);
  }
  bool matchContext(const CompiledRule& rule, size_t, uint32_t*, uint32_t*) const {
    return !rule.hasContext();
  }
  std::array<double, 3> position(size_t i) const { return pool_.positionOf(i); }

 private:
  const SpatialPool& pool_;
};

}  // namespace ontogen
