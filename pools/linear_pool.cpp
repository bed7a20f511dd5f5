#include "pools/linear_pool.h"

#include <algorithm>
#include <stdexcept>

namespace ontogen {

void LinearPool::indexBranches(std::span<const uint8_t> classOf) {
  // A word whose symbols include no bracket has no branch to index (a signal, Koch):
  // nothing is read from the index there, so no pass over the word is made for it.
  if (std::none_of(classOf.begin(), classOf.end(),
                   [](uint8_t symbol) { return symbol & (kSymbolBranchOpen | kSymbolBranchClose); })) {
    partner_.clear();
    return;
  }
  const size_t size = this->size();
  partner_.assign(size, kNoPartner);
  std::vector<uint32_t> open;
  for (uint32_t i = 0; i < size; ++i) {
    uint8_t symbol = classOf[masterAt(i)];
    if (symbol & kSymbolBranchOpen) {
      open.push_back(i);
    } else if ((symbol & kSymbolBranchClose) && !open.empty()) {
      partner_[i] = open.back();
      partner_[open.back()] = i;
      open.pop_back();
    }
  }
}

// The base's pointer to the held word points at this pool's own holding, not the copied one's.
LinearPool::LinearPool(const LinearPool& other)
    : Pool(other), partner_(other.partner_), holding_(other.holding_) {
  compact_ = other.compact_ ? &holding_ : nullptr;
}

LinearPool& LinearPool::operator=(const LinearPool& other) {
  if (this == &other) return *this;
  Pool::operator=(other);
  partner_ = other.partner_;
  holding_ = other.holding_;
  compact_ = other.compact_ ? &holding_ : nullptr;
  return *this;
}

void LinearPool::dropCompactWord() {
  holding_.word = CompactWord(stateCounts_);
  compact_ = nullptr;
  forgetIdReplay();
}

void LinearPool::forgetIdReplay() {
  holding_.ids.replay.reset();
  holding_.ids.pending.store(false, std::memory_order_release);
}

void LinearPool::holdWithoutIds(std::shared_ptr<const IdReplay> replay) {
  if (!compact_ || holding_.word.holdsIds() || !replay)
    throw std::logic_error("ontogen: internal error: a replay of ids for a word that holds them");
  holding_.ids.replay = std::move(replay);
  holding_.ids.pending.store(true, std::memory_order_release);
}

void LinearPool::swapCompactWord(CompactWord& next) {
  if (!compact_) {
    CellArray().swap(cells_);
    StateArray().swap(state_);
    blockOffsets_.clear();
    holding_.word = CompactWord(stateCounts_);
    compact_ = &holding_;
  }
  std::swap(holding_.word, next);
  forgetIdReplay();  // the caller says when the word came without ids (holdWithoutIds)
  ++version_;
}

void LinearPool::storeCompactWord(uint64_t seedKey) {
  if (compact_) return;
  CompactWord word(stateCounts_);
  word.reserve(size(), size(), state_.size());
  for (CellCursor cell = cursor(); !cell.done(); cell.next()) {
    const uint32_t k = static_cast<uint32_t>(cell.index());
    const bool seeded = cell.index() < IdKey::kWhole && mixKey(seedKey, k) == cell.id();
    word.append(cell.master(), seeded ? IdKey{seedKey, k} : IdKey::whole(cell.id()), cell.birth(), cell.state());
  }
  word.finish();
  swapCompactWord(word);
}

void LinearPool::storeRecords() {
  if (!compact_) return;
  readable();
  CellArray cells;
  StateArray state;
  const CompactWord& word = holding_.word;
  cells.reserve(word.size());
  state.reserve(word.valueCount());
  for (CompactWordCursor cell(word); !cell.done(); cell.next()) {
    const uint32_t count = word.stateCount(cell.master());
    cells.push_back(CellRecord{cell.master(), static_cast<uint32_t>(state.size()), cell.birth(), cell.id()});
    state.insert(state.end(), cell.state(), cell.state() + count);
  }
  swapContents(cells, state);  // drops the compact word
}

bool LinearPool::matchLeft(size_t index, std::span<const ContextItem> items, std::span<const uint8_t> classOf,
                           uint32_t* matched) const {
  int64_t pos = static_cast<int64_t>(index);
  for (size_t k = 0; k < items.size(); ++k) {
    for (;;) {
      if (--pos < 0) break;
      uint8_t symbol = classOf[masterAt(static_cast<size_t>(pos))];
      if (symbol & kSymbolBranchClose) {
        if (partner_[pos] != kNoPartner) pos = partner_[pos];  // skip a complete sibling branch
        continue;
      }
      if (symbol & kSymbolBranchOpen) {
        if (items[k].kind == ContextItem::Kind::BranchOpen) break;  // the branch starts here
        continue;                                                   // leave the branch
      }
      if (symbol & kSymbolIgnored) continue;
      break;
    }
    if (pos < 0) return items[k].kind == ContextItem::Kind::End;  // the start of the word
    if (items[k].kind == ContextItem::Kind::End) return false;
    if (items[k].kind == ContextItem::Kind::BranchOpen) {
      if (!(classOf[masterAt(static_cast<size_t>(pos))] & kSymbolBranchOpen)) return false;
      matched[k] = static_cast<uint32_t>(pos);
      continue;
    }
    if (items[k].kind != ContextItem::Kind::Any &&
        (items[k].kind != ContextItem::Kind::Module || masterAt(static_cast<size_t>(pos)) != items[k].master))
      return false;
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

bool LinearPool::matchRight(size_t index, std::span<const ContextItem> items, std::span<const uint8_t> classOf,
                            uint32_t* matched) const {
  const int64_t size = static_cast<int64_t>(this->size());
  int64_t pos = static_cast<int64_t>(index);
  for (size_t k = 0; k < items.size(); ++k) {
    const ContextItem& item = items[k];
    if (item.kind == ContextItem::Kind::BranchClose) {
      // Skip the rest of the current branch, nested branches included, up to its ']'.
      for (;;) {
        if (++pos >= size) return false;
        uint8_t symbol = classOf[masterAt(static_cast<size_t>(pos))];
        if (symbol & kSymbolBranchOpen) {
          if (partner_[pos] == kNoPartner) return false;
          pos = partner_[pos];
        } else if (symbol & kSymbolBranchClose) {
          break;
        }
      }
      matched[k] = static_cast<uint32_t>(pos);
      continue;
    }
    for (;;) {
      if (++pos >= size) return item.kind == ContextItem::Kind::End;  // the end of the word
      uint8_t symbol = classOf[masterAt(static_cast<size_t>(pos))];
      if (symbol & kSymbolIgnored) continue;
      if (symbol & kSymbolBranchOpen) {
        if (item.kind == ContextItem::Kind::BranchOpen) break;  // enter this branch
        if (partner_[pos] == kNoPartner) return false;
        pos = partner_[pos];  // skip the whole branch
        continue;
      }
      if (symbol & kSymbolBranchClose) return item.kind == ContextItem::Kind::End;  // the current branch ends here
      break;
    }
    if (item.kind == ContextItem::Kind::End) return false;
    if (item.kind == ContextItem::Kind::BranchOpen) {
      if (!(classOf[masterAt(static_cast<size_t>(pos))] & kSymbolBranchOpen)) return false;
    } else if (item.kind != ContextItem::Kind::Any && masterAt(static_cast<size_t>(pos)) != item.master) {
      return false;
    }
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

// The word being written has no bracket index: branches are skipped by depth.
bool LinearPool::matchLeftOfEnd(std::span<const CellRecord> cells, std::span<const ContextItem> items,
                                std::span<const uint8_t> classOf, uint32_t* matched) {
  int64_t pos = static_cast<int64_t>(cells.size());
  for (size_t k = 0; k < items.size(); ++k) {
    const ContextItem& item = items[k];
    for (;;) {
      if (--pos < 0) return item.kind == ContextItem::Kind::End;
      const uint8_t symbol = classOf[cells[pos].master];
      if (symbol & kSymbolBranchClose) {
        for (int depth = 1; depth > 0;) {
          if (--pos < 0) return false;
          const uint8_t inner = classOf[cells[pos].master];
          depth += (inner & kSymbolBranchClose) ? 1 : (inner & kSymbolBranchOpen) ? -1 : 0;
        }
        continue;
      }
      if (symbol & kSymbolBranchOpen) {
        if (item.kind == ContextItem::Kind::BranchOpen) break;
        continue;
      }
      if (symbol & kSymbolIgnored) continue;
      break;
    }
    if (item.kind == ContextItem::Kind::End) return false;
    if (item.kind == ContextItem::Kind::BranchOpen) {
      if (!(classOf[cells[pos].master] & kSymbolBranchOpen)) return false;
      matched[k] = static_cast<uint32_t>(pos);
      continue;
    }
    if (item.kind != ContextItem::Kind::Any && cells[pos].master != item.master) return false;
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

// Reading rightwards is reading `reversed` from its end; branches are skipped by depth.
bool LinearPool::matchRightOfReversed(std::span<const CellRecord> reversed, std::span<const ContextItem> items,
                                      std::span<const uint8_t> classOf, uint32_t* matched) {
  int64_t pos = static_cast<int64_t>(reversed.size());
  // From the '[' at pos, to the ']' that closes its branch.
  auto skipBranch = [&] {
    for (int depth = 1; depth > 0;) {
      if (--pos < 0) return false;
      const uint8_t inner = classOf[reversed[pos].master];
      depth += (inner & kSymbolBranchOpen) ? 1 : (inner & kSymbolBranchClose) ? -1 : 0;
    }
    return true;
  };
  for (size_t k = 0; k < items.size(); ++k) {
    const ContextItem& item = items[k];
    if (item.kind == ContextItem::Kind::BranchClose) {
      // Skip the rest of the current branch, nested branches included, up to its ']'.
      for (;;) {
        if (--pos < 0) return false;
        const uint8_t symbol = classOf[reversed[pos].master];
        if (symbol & kSymbolBranchOpen) {
          if (!skipBranch()) return false;
        } else if (symbol & kSymbolBranchClose) {
          break;
        }
      }
      matched[k] = static_cast<uint32_t>(pos);
      continue;
    }
    for (;;) {
      if (--pos < 0) return item.kind == ContextItem::Kind::End;
      const uint8_t symbol = classOf[reversed[pos].master];
      if (symbol & kSymbolIgnored) continue;
      if (symbol & kSymbolBranchOpen) {
        if (item.kind == ContextItem::Kind::BranchOpen) break;  // enter this branch
        if (!skipBranch()) return false;
        continue;
      }
      if (symbol & kSymbolBranchClose) return item.kind == ContextItem::Kind::End;
      break;
    }
    if (item.kind == ContextItem::Kind::End) return false;
    if (item.kind == ContextItem::Kind::BranchOpen) {
      if (!(classOf[reversed[pos].master] & kSymbolBranchOpen)) return false;
    } else if (item.kind != ContextItem::Kind::Any && reversed[pos].master != item.master) {
      return false;
    }
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

}  // namespace ontogen
