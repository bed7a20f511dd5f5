#pragma once
// What rules read around a cell, for each pool kind: its neighbours (for aggregates),
// its positional context (`A(y) me B(z)`) and its position (`me.x`, `me.y`, `me.z`).
// The development of a pool and the rate integrator see pools only through a view.

#include <array>
#include <cstdint>
#include <vector>

#include "lang/program.h"
#include "pools/grid_pool.h"
#include "pools/linear_pool.h"
#include "pools/spatial_pool.h"

namespace ontogen {

class PoolView {
 public:
  virtual ~PoolView() = default;
  virtual const Pool& pool() const = 0;
  /// Replaces `out` with the indices of the cells next to cell i. Empty sites and
  /// missing neighbours are left out.
  virtual void neighbours(size_t i, std::vector<uint32_t>& out) const = 0;
  /// Matches a rule's positional context around cell i; on success the matched cells'
  /// indices are in left[k] and right[k] for the rule's items.
  virtual bool matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const = 0;
  virtual std::array<double, 3> position(size_t i) const = 0;
};

/// The linear pool: neighbours are the branch-aware left neighbour (towards the root)
/// and right neighbour (the next module of the same branch), as context sees them.
/// Call LinearPool::indexBranches before using it on a changed word.
class LinearPoolView final : public PoolView {
 public:
  LinearPoolView(const LinearPool& pool, std::span<const uint8_t> classOf) : pool_(pool), classOf_(classOf) {}
  const Pool& pool() const override { return pool_; }
  void neighbours(size_t i, std::vector<uint32_t>& out) const override;
  bool matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const override;
  std::array<double, 3> position(size_t i) const override { return {static_cast<double>(i), 0, 0}; }

 private:
  const LinearPool& pool_;
  std::span<const uint8_t> classOf_;
};

/// The grid pool: neighbours are the occupied sites of the neighbourhood; a 1-D grid
/// also matches positional context, item k at offset -(k+1) (left) or k+1 (right).
class GridPoolView final : public PoolView {
 public:
  explicit GridPoolView(const GridPool& pool) : pool_(pool) {}
  const Pool& pool() const override { return pool_; }
  void neighbours(size_t i, std::vector<uint32_t>& out) const override;
  bool matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const override;
  std::array<double, 3> position(size_t i) const override;

 private:
  const GridPool& pool_;
};

/// The spatial pool: neighbours are the cells within its radius (SpatialPool::index
/// must be current); positional context does not apply (the compiler rejects it).
class SpatialPoolView final : public PoolView {
 public:
  explicit SpatialPoolView(const SpatialPool& pool) : pool_(pool) {}
  const Pool& pool() const override { return pool_; }
  void neighbours(size_t i, std::vector<uint32_t>& out) const override { pool_.neighbours(i, out); }
  bool matchContext(const CompiledRule& rule, size_t, uint32_t*, uint32_t*) const override {
    return !rule.hasContext();
  }
  std::array<double, 3> position(size_t i) const override { return pool_.positionOf(i); }

 private:
  const SpatialPool& pool_;
};

}  // namespace ontogen
