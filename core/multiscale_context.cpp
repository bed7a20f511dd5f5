#include "core/multiscale_context.h"

namespace ontogen {

namespace {

// A walk over the word, position by position; -1 (left) or size (right) is nowhere.
struct ScaledWord {
  const LinearPool& pool;
  std::span<const uint8_t> classOf;
  std::span<const int32_t> scaleOf;
  int64_t size;

  uint8_t symbol(int64_t pos) const { return classOf[pool.masterAt(static_cast<size_t>(pos))]; }
  int32_t scale(int64_t pos) const { return scaleOf[pool.masterAt(static_cast<size_t>(pos))]; }

  // The module the one at pos grows from: complete branches to its left passed over, the
  // `[` of its own branch left behind, ignored symbols passed over.
  int64_t parent(int64_t pos) const {
    for (;;) {
      if (--pos < 0) return -1;
      const uint8_t s = symbol(pos);
      if (s & kSymbolBranchClose) {
        const uint32_t open = pool.partnerOf(static_cast<size_t>(pos));
        if (open == LinearPool::kNoPartner) return -1;
        pos = open;
        continue;
      }
      if (s & (kSymbolBranchOpen | kSymbolIgnored)) continue;
      return pos;
    }
  }

  // The nearest ancestor of pos at scale `target`: past the complexes of pos (coarser
  // ancestors) when the target is not coarser than pos, then past finer modules.
  int64_t ancestorAtScale(int64_t pos, int32_t target) const {
    const int32_t from = scale(pos);
    pos = parent(pos);
    if (pos < 0) return -1;
    int32_t at = scale(pos);
    if (!(target < from))
      while (at < from) {
        if ((pos = parent(pos)) < 0) return -1;
        at = scale(pos);
      }
    while (at > target) {
      if ((pos = parent(pos)) < 0) return -1;
      at = scale(pos);
    }
    return at == target ? pos : -1;
  }

  // The next position along the word from pos (pos itself when `here`), ignored symbols
  // passed over.
  int64_t next(int64_t pos, bool here) const {
    if (!here) ++pos;
    while (pos < size && (symbol(pos) & kSymbolIgnored)) ++pos;
    return pos;
  }

  // The next module at scale `target` after a module of scale `from` (starting at pos
  // itself when `here`): finer modules passed over unless the target is finer than
  // `from`; a coarser module entered through its components.
  int64_t nextAtScale(int64_t pos, int32_t target, bool here, int32_t from) const {
    if (pos >= size) return size;
    if (!here) from = scale(pos);
    pos = next(pos, here);
    if (!(target > from)) {
      while (pos < size && scale(pos) > target) pos = next(pos, false);
      if (pos >= size) return size;
    }
    if (pos >= size) return size;
    int32_t at = scale(pos);
    if (at < target) {
      int32_t above;
      do {
        pos = next(pos, false);
        if (pos >= size) return size;
        above = at;
        at = scale(pos);
      } while (at > above && at < target);
    }
    return at == target ? pos : size;
  }

  // The `]` that closes the branch holding pos (pos itself when it is one).
  int64_t endOfBranch(int64_t pos) const {
    while (pos < size && !(symbol(pos) & kSymbolBranchClose)) {
      if (symbol(pos) & kSymbolBranchOpen) {
        const uint32_t close = pool.partnerOf(static_cast<size_t>(pos));
        if (close == LinearPool::kNoPartner) return size;
        pos = close;
      }
      ++pos;
    }
    return pos;
  }
};

int32_t itemScale(const ContextItem& item, std::span<const int32_t> scaleOf) {
  return item.kind == ContextItem::Kind::Module ? scaleOf[item.master] : kUnscaled;
}

}  // namespace

bool matchMultiscaleLeft(const LinearPool& pool, size_t index, std::span<const ContextItem> items,
                         std::span<const uint8_t> classOf, std::span<const int32_t> scaleOf, uint32_t* matched) {
  const ScaledWord word{pool, classOf, scaleOf, static_cast<int64_t>(pool.size())};
  int64_t pos = static_cast<int64_t>(index);
  for (size_t k = 0; k < items.size(); ++k) {
    // The compiler admits module patterns alone on this side (lang/compile_scales.cpp).
    pos = word.ancestorAtScale(pos, itemScale(items[k], scaleOf));
    if (pos < 0 || pool.masterAt(static_cast<size_t>(pos)) != items[k].master) return false;
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

bool matchMultiscaleRight(const LinearPool& pool, size_t index, std::span<const ContextItem> items,
                          std::span<const uint8_t> classOf, std::span<const int32_t> scaleOf, uint32_t* matched) {
  const ScaledWord word{pool, classOf, scaleOf, static_cast<int64_t>(pool.size())};
  if (items.empty()) return true;
  int64_t pos = word.nextAtScale(static_cast<int64_t>(index) + 1, itemScale(items[0], scaleOf), true,
                                 word.scale(static_cast<int64_t>(index)));
  size_t k = 0;
  while (pos < word.size && k < items.size()) {
    const ContextItem& item = items[k];
    const uint8_t symbol = word.symbol(pos);
    bool advance = true;
    if (item.kind == ContextItem::Kind::BranchOpen) {
      if (!(symbol & kSymbolBranchOpen)) return false;
    } else if (item.kind == ContextItem::Kind::BranchClose) {
      pos = word.endOfBranch(pos);  // the rest of the branch the pattern's `[` entered
      if (pos >= word.size) return false;
    } else if (symbol & kSymbolBranchClose) {
      return false;  // the module's branch ends before the pattern does
    } else if (symbol & kSymbolBranchOpen) {
      // A branch where a module is looked for (the pattern's scale is that of brackets):
      // passed over whole.
      const uint32_t close = pool.partnerOf(static_cast<size_t>(pos));
      if (close == LinearPool::kNoPartner) return false;
      pos = close;
      advance = false;
    } else if (pool.masterAt(static_cast<size_t>(pos)) != item.master) {
      return false;
    }
    if (advance) matched[k++] = static_cast<uint32_t>(pos);
    if (k < items.size()) pos = word.nextAtScale(pos, itemScale(items[k], scaleOf), false, 0);
  }
  return k == items.size();
}

}  // namespace ontogen
