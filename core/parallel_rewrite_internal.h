#pragma once
// What the compact word's strategies (core/compact_rewrite.cpp and beside it) share,
// private to them: how many slices a thread takes, a word's labels as they read them, and
// a rule's context of labels matched by position in them (ParallelRewrite::LabelRule).

#include <cstddef>
#include <cstdint>

#include "core/parallel_rewrite.h"
#include "pools/compact_word.h"

namespace ontogen {

/// Slices per thread: enough that one slice heavier than the others does not hold up the
/// rest, few enough that their bookkeeping costs nothing.
inline constexpr size_t kSlicesPerThread = 4;

/// The labels of a compact word.
struct CompactLabels {
  const CompactWord& word;
  uint32_t operator[](size_t i) const { return word.label(i); }
};
/// The same for a compact word of one-byte labels, the usual case, without a test per read.
struct ByteLabels {
  const uint8_t* labels;
  uint32_t operator[](size_t i) const { return labels[i]; }
};

// As LinearPool::matchLeft and matchRight match in a plain word, from the codes labelRule made.
template <class Labels>
inline bool ParallelRewrite::matchesByPosition(const Labels& labels, size_t size, const LabelRule& choice, size_t i) {
  for (size_t k = 0; k < choice.leftCount; ++k) {
    const int32_t expected = choice.left[k];
    if (i < k + 1) return expected == kEndLabel;  // the start of the word
    if (expected != kAnyLabel && (expected < 0 || labels[i - 1 - k] != static_cast<uint32_t>(expected))) return false;
  }
  for (size_t k = 0; k < choice.rightCount; ++k) {
    const int32_t expected = choice.right[k];
    if (i + 1 + k >= size) return expected == kEndLabel;  // the end of the word
    if (expected != kAnyLabel && (expected < 0 || labels[i + 1 + k] != static_cast<uint32_t>(expected))) return false;
  }
  return true;
}

}  // namespace ontogen
