#pragma once
// The linear pool: the L-system string. Cells are kept in one array in word order;
// successors are written in place of their predecessor when the engine rebuilds the
// word. Context is branch-aware as in The Algorithmic Beauty of Plants, section 1.8:
//  - the left context is found on the path towards the root: a `[` to the left is left
//    behind (its parent comes before it) and a complete branch `[...]` is skipped;
//  - the right context skips whole branches unless the pattern enters one with `[`; a
//    `]` in the pattern skips the rest of the current branch; the end of the current
//    branch (`]`) has no right neighbour;
//  - symbols marked kSymbolIgnored are left out in both directions.

#include <cstdint>
#include <span>
#include <vector>

#include "pools/pool.h"

namespace ontogen {

/// One position of a context pattern: a module of a given master, a bracket, any module,
/// or the end: nothing more on that side (the start of the word on the left, the end of
/// the branch or the word on the right), always the farthest item.
struct ContextItem {
  enum class Kind : uint8_t { Module, BranchOpen, BranchClose, Any, End };
  Kind kind = Kind::Module;
  uint32_t master = 0;
};

class LinearPool final : public Pool {
 public:
  LinearPool() = default;
  LinearPool(const LinearPool& other);
  LinearPool& operator=(const LinearPool& other);

  PoolKind kind() const override { return PoolKind::Linear; }
  int contextDimension() const override { return 1; }
  std::unique_ptr<Pool> clone() const override { return std::make_unique<LinearPool>(*this); }

  // --- Compact words (docs/COMPACT_WORDS.md). The pool starts with records; its
  // development moves it to a compact word while it rewrites in that form, and back. Both
  // need countValues. Readers see the same cells either way.

  /// An empty word laid out for this pool's masters, for a writer of the next word.
  CompactWord emptyCompactWord() const { return CompactWord(stateCounts_); }
  /// Replaces the contents with `next`, keeping the old word's storage in `next`.
  void swapCompactWord(CompactWord& next);
  /// Encodes the records as a compact word and frees them. Records do not say which ids
  /// share a lineage key: cell i whose id is mixKey(seedKey, i), as an axiom's cells are
  /// (core/development.h), is written as the i-th of seedKey, any other id whole.
  void storeCompactWord(uint64_t seedKey);
  /// Decodes the compact word into records and frees it.
  void storeRecords();
  /// For core/: the compact word just swapped in was written without ids, and `replay`
  /// makes them again.
  void holdWithoutIds(std::shared_ptr<const IdReplay> replay);
  /// The bytes storeRecords makes: the records of the compact word and their values (0
  /// for a pool of records).
  size_t recordBytes() const {
    return compact_ ? holding_.word.size() * sizeof(CellRecord) + holding_.word.valueCount() * sizeof(double) : 0;
  }

  /// Computes the matching bracket of every `[` and `]` for the current cells.
  /// classOf[master] is the SymbolClass of each master. Call after the word changes and
  /// before matching.
  void indexBranches(std::span<const uint8_t> classOf);

  /// Matches a left context given nearest-first (for `A B < C`: B, then A). On success
  /// matched[k] is the index of the cell that matched items[k]. A `[` item matches the
  /// opening of the branch the cell starts (complete sibling branches passed over).
  bool matchLeft(size_t index, std::span<const ContextItem> items, std::span<const uint8_t> classOf,
                 uint32_t* matched) const;
  /// Matches a right context given in text order. Brackets in items enter a branch (`[`)
  /// or leave the current one (`]`); matched[k] is meaningful for module items only.
  bool matchRight(size_t index, std::span<const ContextItem> items, std::span<const uint8_t> classOf,
                  uint32_t* matched) const;

  /// Matches a left context, nearest first, against the end of `cells`, a word being
  /// written (which has no bracket index), as matchLeft reads a word; matched[k] indexes
  /// `cells`.
  static bool matchLeftOfEnd(std::span<const CellRecord> cells, std::span<const ContextItem> items,
                             std::span<const uint8_t> classOf, uint32_t* matched);

  /// Matches a right context, text order, against `reversed`: the part of a word right of
  /// a module, written right to left (its nearest cell last), read as matchRight reads a
  /// word; matched[k] indexes `reversed`.
  static bool matchRightOfReversed(std::span<const CellRecord> reversed, std::span<const ContextItem> items,
                                   std::span<const uint8_t> classOf, uint32_t* matched);

  /// The master (label) of cell i, read from the records or from the compact word: the
  /// one view of a word that every context match reads, whichever form holds it.
  uint32_t masterAt(size_t i) const { return compact_ ? holding_.word.label(i) : cells_[i].master; }

  /// Matching bracket of cell i, or kNoPartner (an unmatched bracket or not a bracket).
  uint32_t partnerOf(size_t i) const { return i < partner_.size() ? partner_[i] : kNoPartner; }
  static constexpr uint32_t kNoPartner = UINT32_MAX;

 private:
  void dropCompactWord() override;
  /// The word now held holds its ids (swapped in, or dropped).
  void forgetIdReplay();

  std::vector<uint32_t> partner_;
  CompactHolding holding_;  // the compact word, while Pool::compact_ points here
};

}  // namespace ontogen
