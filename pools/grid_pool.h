#pragma once
// The grid pool: an N-dimensional array of sites (1-, 2- or 3-D), each empty or holding
// one cell (paper 002, section 2.1, Fig. 3). Cells are kept in site order, the first
// axis fastest, so interpretation and words walk the grid row by row. Neighbours are
// the von Neumann (faces) or Moore (faces, edges and corners) neighbourhood, in a fixed
// order (offsets in lexicographic order, last axis slowest); beyond the edge the
// boundary decides: wrap (a torus), clamp (the edge site stands in for the missing one,
// so a gradient across the edge is zero) or closed (no neighbour there).

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "pools/pool.h"

namespace ontogen {

enum class GridBoundary : uint8_t { Closed, Wrap, Clamp };
enum class GridNeighbourhood : uint8_t { VonNeumann, Moore };

std::string_view gridBoundaryName(GridBoundary boundary);
std::string_view gridNeighbourhoodName(GridNeighbourhood neighbourhood);

struct GridShape {
  int dimensions = 1;
  std::array<uint32_t, 3> size{1, 1, 1};  ///< sites along each axis (1 beyond `dimensions`)
  GridBoundary boundary = GridBoundary::Closed;
  GridNeighbourhood neighbourhood = GridNeighbourhood::VonNeumann;

  uint64_t siteCount() const { return uint64_t{size[0]} * size[1] * size[2]; }
};

using GridCoordinates = std::array<int64_t, 3>;

class GridPool final : public Pool {
 public:
  static constexpr uint32_t kEmpty = UINT32_MAX;
  static constexpr int kMaxNeighbours = 26;

  explicit GridPool(const GridShape& shape = {});

  PoolKind kind() const override { return PoolKind::Grid; }
  int contextDimension() const override { return shape_.dimensions; }
  std::unique_ptr<Pool> clone() const override { return std::make_unique<GridPool>(*this); }

  const GridShape& shape() const { return shape_; }
  uint32_t siteCount() const { return static_cast<uint32_t>(cellAt_.size()); }
  /// The site of the i-th cell.
  uint32_t siteOf(size_t cell) const { return siteOf_[cell]; }
  /// The index of the cell at a site, or kEmpty.
  uint32_t cellAt(uint32_t site) const { return cellAt_[site]; }
  GridCoordinates coordinates(uint32_t site) const;
  /// The site at coordinates after the boundary rule, or kEmpty when closed and outside.
  uint32_t siteAt(GridCoordinates coordinates) const;

  /// The neighbourhood's offsets, in the order neighbourSites reports them.
  std::span<const GridCoordinates> offsets() const { return offsets_; }
  /// Writes the neighbour sites of a site (kEmpty where a closed boundary leaves none),
  /// one per offset; returns the number of offsets.
  int neighbourSites(uint32_t site, uint32_t* out) const;

  /// Replaces the contents with cells in ascending site order; `sites[i]` is the site
  /// of cell i. The vectors receive the old contents, to reuse their memory.
  void assign(CellArray& cells, StateArray& state, std::vector<uint32_t>& sites);
  /// Places a cell at an empty site (set-up; keeps site order by re-sorting).
  void place(uint32_t site, CellRecord cell, const double* values, uint32_t count);

 private:
  void reindex();

  GridShape shape_;
  std::vector<GridCoordinates> offsets_;
  std::vector<uint32_t> siteOf_;  ///< per cell
  std::vector<uint32_t> cellAt_;  ///< per site
};

}  // namespace ontogen
