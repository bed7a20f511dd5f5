#include "pools/pool.h"

#include <algorithm>

namespace ontogen {

std::string_view poolKindName(PoolKind kind) {
  switch (kind) {
    case PoolKind::Linear:
      return "linear";
    case PoolKind::Grid:
      return "grid";
    case PoolKind::Spatial:
      return "spatial";
  }
  return "linear";
}

void Pool::append(CellRecord cell, const double* values, uint32_t count) {
  cell.state = static_cast<uint32_t>(state_.size());
  state_.insert(state_.end(), values, values + count);
  cells_.push_back(cell);
  ++version_;
}

void Pool::swapContents(CellArray& cells, StateArray& state) {
  cells_.swap(cells);
  state_.swap(state);
  ++version_;
}

void Pool::reserve(size_t cells, size_t values) {
  cells_.reserve(cells);
  state_.reserve(values);
}

void Pool::clear() {
  cells_.clear();
  state_.clear();
  ++version_;
}

}  // namespace ontogen
