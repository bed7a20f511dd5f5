#include "pools/grid_pool.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace ontogen {

std::string_view gridBoundaryName(GridBoundary boundary) {
  switch (boundary) {
    case GridBoundary::Closed:
      return "closed";
    case GridBoundary::Wrap:
      return "wrap";
    case GridBoundary::Clamp:
      return "clamp";
  }
  return "closed";
}

std::string_view gridNeighbourhoodName(GridNeighbourhood neighbourhood) {
  return neighbourhood == GridNeighbourhood::Moore ? "moore" : "vonneumann";
}

GridPool::GridPool(const GridShape& shape) : shape_(shape) {
  if (shape.dimensions < 1 || shape.dimensions > 3) throw std::invalid_argument("a grid has 1 to 3 dimensions");
  for (int axis = 0; axis < 3; ++axis)
    if (shape_.size[axis] == 0 || (axis >= shape.dimensions && shape_.size[axis] != 1))
      throw std::invalid_argument("grid sizes must be positive, and 1 beyond the grid's dimensions");
  if (shape.siteCount() >= kEmpty) throw std::invalid_argument("a grid has fewer than 2^32 - 1 sites");
  cellAt_.assign(shape.siteCount(), kEmpty);
  // Offsets in lexicographic order with the last axis slowest: (-1,-1) (0,-1) (1,-1) ...
  const int range[3] = {1, shape.dimensions > 1 ? 1 : 0, shape.dimensions > 2 ? 1 : 0};
  for (int64_t dz = -range[2]; dz <= range[2]; ++dz)
    for (int64_t dy = -range[1]; dy <= range[1]; ++dy)
      for (int64_t dx = -range[0]; dx <= range[0]; ++dx) {
        int64_t manhattan = std::abs(dx) + std::abs(dy) + std::abs(dz);
        if (manhattan == 0) continue;
        if (shape.neighbourhood == GridNeighbourhood::VonNeumann && manhattan != 1) continue;
        offsets_.push_back({dx, dy, dz});
      }
}

GridCoordinates GridPool::coordinates(uint32_t site) const {
  const uint64_t nx = shape_.size[0], ny = shape_.size[1];
  return {static_cast<int64_t>(site % nx), static_cast<int64_t>(site / nx % ny),
          static_cast<int64_t>(site / (nx * ny))};
}

uint32_t GridPool::siteAt(GridCoordinates c) const {
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t n = shape_.size[axis];
    if (c[axis] >= 0 && c[axis] < n) continue;
    switch (shape_.boundary) {
      case GridBoundary::Closed:
        return kEmpty;
      case GridBoundary::Wrap:
        c[axis] = ((c[axis] % n) + n) % n;
        break;
      case GridBoundary::Clamp:
        c[axis] = std::clamp<int64_t>(c[axis], 0, n - 1);
        break;
    }
  }
  return static_cast<uint32_t>(c[0] + shape_.size[0] * (c[1] + uint64_t{shape_.size[1]} * c[2]));
}

int GridPool::neighbourSites(uint32_t site, uint32_t* out) const {
  const GridCoordinates here = coordinates(site);
  int n = 0;
  for (const GridCoordinates& offset : offsets_)
    out[n++] = siteAt({here[0] + offset[0], here[1] + offset[1], here[2] + offset[2]});
  return n;
}

void GridPool::assign(CellArray& cells, StateArray& state, std::vector<uint32_t>& sites) {
  swapContents(cells, state);
  siteOf_.swap(sites);
  reindex();
}

void GridPool::place(uint32_t site, CellRecord cell, const double* values, uint32_t count) {
  if (site >= cellAt_.size()) throw std::out_of_range("no such grid site");
  if (cellAt_[site] != kEmpty) throw std::logic_error("the grid site is taken");
  append(cell, values, count);
  siteOf_.push_back(site);
  // Keep site order: placements come in any order while a world is set up.
  if (siteOf_.size() > 1 && siteOf_[siteOf_.size() - 2] > site) {
    std::vector<uint32_t> order(siteOf_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return siteOf_[a] < siteOf_[b]; });
    CellArray sortedCells;
    std::vector<uint32_t> sortedSites;
    for (uint32_t i : order) {
      sortedCells.push_back(cells_[i]);
      sortedSites.push_back(siteOf_[i]);
    }
    cells_.swap(sortedCells);
    siteOf_.swap(sortedSites);
    ++version_;
  }
  reindex();
}

void GridPool::reindex() {
  std::fill(cellAt_.begin(), cellAt_.end(), kEmpty);
  for (size_t i = 0; i < siteOf_.size(); ++i) cellAt_[siteOf_[i]] = static_cast<uint32_t>(i);
}

}  // namespace ontogen
