#pragma once
// Walks a compact word's labels, values and run births, in order, whether it holds its
// ids or not: for a reader that wants no ids (`ontogen word` as text), so that a word
// grown without ids (docs/COMPACT_WORDS.md, "Words without ids") is read as it is held,
// without the replay that makes its ids again and takes more time and memory than the
// word. CompactWordCursor (pools/compact_word.h) is the cursor that gives everything.

#include <cstddef>
#include <cstdint>

#include "pools/compact_word.h"

namespace ontogen {

class LabelCursor {
 public:
  explicit LabelCursor(const CompactWord& word)
      : word_(&word),
        values_(word.values_.data()),
        runStarts_(word.runStarts_.data()),
        birthIndex_(word.birthIndex_.data()),
        births_(word.births_.data()),
        size_(word.size_) {
    if (size_ > 0) birth_ = births_[birthIndex_[0]];
  }

  bool done() const { return index_ >= size_; }
  void next() {
    value_ += word_->stateCount(master());
    if (++index_ >= size_) return;
    if ((runStarts_[index_ / CompactWord::kBlock] >> (index_ % CompactWord::kBlock)) & 1u)
      birth_ = births_[birthIndex_[++run_]];
  }
  size_t size() const { return size_; }

  // The module under the cursor (not done()).
  size_t index() const { return index_; }
  uint32_t master() const { return word_->label(index_); }
  const double* state() const { return values_ + value_; }
  /// The birth of the module's run: the module's own, except for a timeless module of a
  /// word held without ids, which joins the run beside it (docs/COMPACT_WORDS.md,
  /// "Timeless modules join runs").
  double birth() const { return birth_; }

 private:
  const CompactWord* word_;
  const double* values_;
  const uint64_t* runStarts_;
  const uint32_t* birthIndex_;
  const double* births_;
  size_t size_;
  size_t index_ = 0, run_ = 0, value_ = 0;
  double birth_ = 0;
};

}  // namespace ontogen
