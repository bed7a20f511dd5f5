#include "pools/pool.h"

#include <algorithm>
#include <stdexcept>

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

void Pool::noRecords() {
  throw std::logic_error("ontogen: internal error: the records of a pool that holds a compact word");
}

void Pool::append(CellRecord cell, const double* values, uint32_t count) {
  if (compact_) noRecords();
  cell.state = static_cast<uint32_t>(state_.size());
  if (anyState_ && cells_.size() % kStateBlock == 0) blockOffsets_.push_back(cell.state);
  state_.insert(state_.end(), values, values + count);
  cells_.push_back(cell);
  ++version_;
}

void Pool::swapContents(CellArray& cells, StateArray& state) {
  if (compact_) dropCompactWord();
  cells_.swap(cells);
  state_.swap(state);
  indexValues();
  ++version_;
}

// The replay is run by the first reader; the others wait on the lock. The cells do not
// change (the structure version stays), only how the word holds them.
void Pool::restoreIds() const {
  CompactHolding::IdsToRestore& ids = compact_->ids;
  std::lock_guard<std::mutex> hold(*ids.lock);
  if (!ids.pending.load(std::memory_order_acquire)) return;
  CompactWord withIds = ids.replay->replay(compact_->word.bytes());
  if (withIds.size() != compact_->word.size() || !withIds.holdsIds())
    throw std::logic_error("ontogen: internal error: a replay of ids gave another word");
  compact_->word = std::move(withIds);
  ids.replay.reset();
  ids.pending.store(false, std::memory_order_release);
}

void Pool::countValues(std::vector<uint32_t> perMaster) {
  if (compact_) noRecords();
  stateCounts_ = std::move(perMaster);
  counted_ = true;
  anyState_ = std::any_of(stateCounts_.begin(), stateCounts_.end(), [](uint32_t n) { return n > 0; });
  indexValues();
}

// One pass over the masters, only where some master has values.
void Pool::indexValues() {
  if (!anyState_) return;
  const size_t size = cells_.size();
  blockOffsets_.resize((size + kStateBlock - 1) / kStateBlock);
  const CellRecord* cells = cells_.data();
  const uint32_t* counts = stateCounts_.data();
  uint32_t offset = 0;
  for (size_t block = 0, first = 0; first < size; ++block, first += kStateBlock) {
    blockOffsets_[block] = offset;
    const size_t last = std::min(size, first + kStateBlock);
    for (size_t i = first; i < last; ++i) offset += counts[cells[i].master];
  }
}

void Pool::reserve(size_t cells, size_t values) {
  cells_.reserve(cells);
  state_.reserve(values);
}

void Pool::clear() {
  if (compact_) dropCompactWord();
  cells_.clear();
  state_.clear();
  blockOffsets_.clear();
  ++version_;
}

}  // namespace ontogen
