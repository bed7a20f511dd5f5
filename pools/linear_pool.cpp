#include "pools/linear_pool.h"

namespace ontogen {

void LinearPool::indexBranches(std::span<const uint8_t> classOf) {
  partner_.assign(cells_.size(), kNoPartner);
  std::vector<uint32_t> open;
  for (uint32_t i = 0; i < cells_.size(); ++i) {
    uint8_t symbol = classOf[cells_[i].master];
    if (symbol & kSymbolBranchOpen) {
      open.push_back(i);
    } else if ((symbol & kSymbolBranchClose) && !open.empty()) {
      partner_[i] = open.back();
      partner_[open.back()] = i;
      open.pop_back();
    }
  }
}

bool LinearPool::matchLeft(size_t index, std::span<const ContextItem> items, std::span<const uint8_t> classOf,
                           uint32_t* matched) const {
  int64_t pos = static_cast<int64_t>(index);
  for (size_t k = 0; k < items.size(); ++k) {
    for (;;) {
      if (--pos < 0) return false;
      uint8_t symbol = classOf[cells_[pos].master];
      if (symbol & kSymbolBranchClose) {
        if (partner_[pos] != kNoPartner) pos = partner_[pos];  // skip a complete sibling branch
        continue;
      }
      if (symbol & (kSymbolBranchOpen | kSymbolIgnored)) continue;  // leave the branch / ignore
      break;
    }
    if (items[k].kind != ContextItem::Kind::Any &&
        (items[k].kind != ContextItem::Kind::Module || cells_[pos].master != items[k].master))
      return false;
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

bool LinearPool::matchRight(size_t index, std::span<const ContextItem> items, std::span<const uint8_t> classOf,
                            uint32_t* matched) const {
  const int64_t size = static_cast<int64_t>(cells_.size());
  int64_t pos = static_cast<int64_t>(index);
  for (size_t k = 0; k < items.size(); ++k) {
    const ContextItem& item = items[k];
    if (item.kind == ContextItem::Kind::BranchClose) {
      // Skip the rest of the current branch, nested branches included, up to its ']'.
      for (;;) {
        if (++pos >= size) return false;
        uint8_t symbol = classOf[cells_[pos].master];
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
      if (++pos >= size) return false;
      uint8_t symbol = classOf[cells_[pos].master];
      if (symbol & kSymbolIgnored) continue;
      if (symbol & kSymbolBranchOpen) {
        if (item.kind == ContextItem::Kind::BranchOpen) break;  // enter this branch
        if (partner_[pos] == kNoPartner) return false;
        pos = partner_[pos];  // skip the whole branch
        continue;
      }
      if (symbol & kSymbolBranchClose) return false;  // the current branch ends here
      break;
    }
    if (item.kind == ContextItem::Kind::BranchOpen) {
      if (!(classOf[cells_[pos].master] & kSymbolBranchOpen)) return false;
    } else if (item.kind != ContextItem::Kind::Any && cells_[pos].master != item.master) {
      return false;
    }
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

}  // namespace ontogen
