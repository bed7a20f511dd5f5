#pragma once
// How many times each label below a bound occurs in a string of one-byte labels: what a
// table rewrite sizes the next word by (TableRewrite::bound).
//
// A histogram (one increment a label, each waiting on the memory it adds to) took 15 % of
// Koch's growth. Here four labels at a time are compared with 32 bytes and counted in
// byte counters, emptied before they can wrap: GCC and clang turn the comparisons into
// vector ones, and a pass takes about a seventh of the histogram's time. Past 16 labels
// the passes would cost more than the histogram, which is kept for them.

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace ontogen {

namespace label_counts_detail {

// Adds the counts of labels first .. first + 3 in labels[0, n) to out[0, 4).
inline void addCountsOfFour(const uint8_t* labels, size_t n, uint8_t first, uint64_t* out) {
  constexpr size_t kLanes = 32;
  constexpr size_t kRounds = 255;  // a byte counter gains at most one a round
  size_t i = 0;
  while (i + kLanes <= n) {
    uint8_t counters[4][kLanes] = {};
    const size_t rounds = std::min(kRounds, (n - i) / kLanes);
    for (size_t round = 0; round < rounds; ++round, i += kLanes) {
      const uint8_t* chunk = labels + i;
      for (size_t lane = 0; lane < kLanes; ++lane) {
        const uint8_t offset = static_cast<uint8_t>(chunk[lane] - first);
        counters[0][lane] += offset == 0;
        counters[1][lane] += offset == 1;
        counters[2][lane] += offset == 2;
        counters[3][lane] += offset == 3;
      }
    }
    for (size_t k = 0; k < 4; ++k)
      for (size_t lane = 0; lane < kLanes; ++lane) out[k] += counters[k][lane];
  }
  for (; i < n; ++i) {
    const uint8_t offset = static_cast<uint8_t>(labels[i] - first);
    if (offset < 4) ++out[offset];
  }
}

}  // namespace label_counts_detail

/// Sets counts[l], for each l < labelCount (at most 256), to the number of times l
/// occurs in labels[0, n).
inline void countLabels(const uint8_t* labels, size_t n, size_t labelCount, uint64_t* counts) {
  std::fill(counts, counts + labelCount, uint64_t{0});
  if (labelCount <= 16) {
    for (size_t first = 0; first < labelCount; first += 4) {
      uint64_t four[4] = {};
      label_counts_detail::addCountsOfFour(labels, n, static_cast<uint8_t>(first), four);
      std::copy_n(four, std::min<size_t>(4, labelCount - first), counts + first);
    }
    return;
  }
  uint64_t histogram[4][256] = {};  // four, so that equal labels in a row do not wait on each other
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    ++histogram[0][labels[i]];
    ++histogram[1][labels[i + 1]];
    ++histogram[2][labels[i + 2]];
    ++histogram[3][labels[i + 3]];
  }
  for (; i < n; ++i) ++histogram[0][labels[i]];
  for (size_t label = 0; label < labelCount; ++label)
    counts[label] = histogram[0][label] + histogram[1][label] + histogram[2][label] + histogram[3][label];
}

}  // namespace ontogen
