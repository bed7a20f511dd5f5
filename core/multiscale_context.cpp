#include "core/multiscale_context.h"

namespace ontogen {

namespace {

// The word a walk reads: the pool, whose brackets are indexed, or the word being
// written, whose branches are found by depth.
struct PoolWord {
  const LinearPool& pool;
  uint32_t master(int64_t pos) const { return pool.masterAt(static_cast<size_t>(pos)); }
  int64_t partner(int64_t pos, const std::span<const uint8_t>) const {
    const uint32_t other = pool.partnerOf(static_cast<size_t>(pos));
    return other == LinearPool::kNoPartner ? -1 : other;
  }
};

struct WrittenCells {
  std::span<const CellRecord> cells;
  uint32_t master(int64_t pos) const { return cells[static_cast<size_t>(pos)].master; }
  // The `[` of the `]` at pos (the walk goes left only).
  int64_t partner(int64_t pos, const std::span<const uint8_t> classOf) const {
    for (int depth = 1; depth > 0;) {
      if (--pos < 0) return -1;
      const uint8_t inner = classOf[cells[static_cast<size_t>(pos)].master];
      depth += (inner & kSymbolBranchClose) ? 1 : (inner & kSymbolBranchOpen) ? -1 : 0;
    }
    return pos;
  }
};

// A walk over the word, position by position; -1 (left) or size (right) is nowhere.
template <typename Word>
struct ScaledWord {
  Word word;
  std::span<const uint8_t> classOf;
  std::span<const int32_t> scaleOf;
  bool levels;  // L-Py's multi-level matching: only modules of the pattern's level count
  int64_t size;

  uint8_t symbol(int64_t pos) const { return classOf[word.master(pos)]; }
  int32_t scale(int64_t pos) const { return scaleOf[word.master(pos)]; }

  // The module the one at pos grows from: complete branches to its left passed over, the
  // `[` of its own branch left behind, ignored symbols passed over.
  int64_t parent(int64_t pos) const {
    for (;;) {
      if (--pos < 0) return -1;
      const uint8_t s = symbol(pos);
      if (s & kSymbolBranchClose) {
        if ((pos = word.partner(pos, classOf)) < 0) return -1;
        continue;
      }
      if (s & (kSymbolBranchOpen | kSymbolIgnored)) continue;
      return pos;
    }
  }

  // The nearest ancestor at scale `target` of a module of scale `from` at pos: past its
  // complexes (coarser ancestors) when the target is not coarser than it, then past finer
  // modules.
  int64_t ancestorAtScale(int64_t pos, int32_t from, int32_t target) const {
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

  // The nearest ancestor of the pattern's scale or level.
  int64_t ancestor(int64_t pos, int32_t from, int32_t target) const {
    if (!levels) return ancestorAtScale(pos, from, target);
    do pos = parent(pos);
    while (pos >= 0 && scale(pos) != target);
    return pos;
  }

  // The next module of the pattern's scale or level.
  int64_t following(int64_t pos, int32_t target, bool here, int32_t from) const {
    if (!levels) return nextAtScale(pos, target, here, from);
    if (pos >= size) return size;
    pos = next(pos, here);
    while (pos < size && scale(pos) != target) pos = next(pos, false);
    return pos;
  }

  // The `]` that closes the branch holding pos (pos itself when it is one).
  int64_t endOfBranch(int64_t pos) const {
    while (pos < size && !(symbol(pos) & kSymbolBranchClose)) {
      if (symbol(pos) & kSymbolBranchOpen) {
        if ((pos = word.partner(pos, classOf)) < 0) return size;
      }
      ++pos;
    }
    return pos;
  }
};

int32_t itemScale(const ContextItem& item, std::span<const int32_t> scaleOf) {
  return item.kind == ContextItem::Kind::Module ? scaleOf[item.master] : kUnscaled;
}

// Matches a left context, nearest first, from a module of scale `from` at `pos`. The
// compiler admits module patterns alone on this side (lang/compile_scales.cpp).
template <typename Word>
bool matchLeft(const ScaledWord<Word>& word, int64_t pos, int32_t from, std::span<const ContextItem> items,
               std::span<const int32_t> scaleOf, uint32_t* matched) {
  for (size_t k = 0; k < items.size(); ++k) {
    pos = word.ancestor(pos, from, itemScale(items[k], scaleOf));
    if (pos < 0 || word.word.master(pos) != items[k].master) return false;
    from = word.scale(pos);
    matched[k] = static_cast<uint32_t>(pos);
  }
  return true;
}

}  // namespace

bool matchMultiscaleLeft(const LinearPool& pool, size_t index, std::span<const ContextItem> items,
                         std::span<const uint8_t> classOf, const ScaleTable& scales, uint32_t* matched) {
  const std::span<const int32_t> scaleOf(scales.of);
  const ScaledWord<PoolWord> word{PoolWord{pool}, classOf, scaleOf, scales.levels, static_cast<int64_t>(pool.size())};
  const int64_t at = static_cast<int64_t>(index);
  return matchLeft(word, at, word.scale(at), items, scaleOf, matched);
}

bool matchMultiscaleNewLeft(std::span<const CellRecord> written, uint32_t master, std::span<const ContextItem> items,
                            std::span<const uint8_t> classOf, const ScaleTable& scales, uint32_t* matched) {
  // The module stands after what is written, as L-Py places it to read its scale.
  const std::span<const int32_t> scaleOf(scales.of);
  const ScaledWord<WrittenCells> word{WrittenCells{written}, classOf, scaleOf, scales.levels,
                                      static_cast<int64_t>(written.size())};
  return matchLeft(word, word.size, scaleOf[master], items, scaleOf, matched);
}

bool matchMultiscaleRight(const LinearPool& pool, size_t index, std::span<const ContextItem> items,
                          std::span<const uint8_t> classOf, const ScaleTable& scales, uint32_t* matched) {
  const std::span<const int32_t> scaleOf(scales.of);
  const ScaledWord<PoolWord> word{PoolWord{pool}, classOf, scaleOf, scales.levels, static_cast<int64_t>(pool.size())};
  if (items.empty()) return true;
  int64_t pos = word.following(static_cast<int64_t>(index) + 1, itemScale(items[0], scaleOf), true,
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
      if ((pos = word.word.partner(pos, classOf)) < 0) return false;
      advance = false;
    } else if (pool.masterAt(static_cast<size_t>(pos)) != item.master) {
      return false;
    }
    if (advance) matched[k++] = static_cast<uint32_t>(pos);
    if (k < items.size()) pos = word.following(pos, itemScale(items[k], scaleOf), false, 0);
  }
  return k == items.size();
}

}  // namespace ontogen
