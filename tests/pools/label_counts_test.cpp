// Counting labels (pools/label_counts.h) agrees with counting them one by one, for every
// number of labels that takes the passes of four or the histogram, at lengths on either
// side of where the byte counters are emptied, and from an unaligned start.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "pools/label_counts.h"

namespace ontogen {
namespace {

std::vector<uint64_t> countedOneByOne(const uint8_t* labels, size_t n, size_t labelCount) {
  std::vector<uint64_t> counts(labelCount, 0);
  for (size_t i = 0; i < n; ++i)
    if (labels[i] < labelCount) ++counts[labels[i]];
  return counts;
}

TEST(LabelCounts, AgreeWithCountingOneByOne) {
  std::mt19937 random(7);
  constexpr size_t kWhereCountersEmpty = 32 * 255;
  const std::vector<size_t> lengths = {0, 1, 31, 32, 33, kWhereCountersEmpty - 1, kWhereCountersEmpty,
                                       kWhereCountersEmpty + 1, 3 * kWhereCountersEmpty + 17, 100003};
  for (const size_t labelCount : {1, 2, 3, 4, 5, 8, 13, 16, 17, 40, 256}) {
    // Labels drawn from more than are counted, so that the others are left out.
    const size_t drawnFrom = labelCount == 256 ? 256 : labelCount + 3;
    std::vector<uint8_t> word(100003 + 5);
    for (uint8_t& label : word) label = static_cast<uint8_t>(random() % drawnFrom);
    for (const size_t n : lengths) {
      for (const size_t start : {size_t{0}, size_t{5}}) {
        std::vector<uint64_t> counts(labelCount, 99);
        countLabels(word.data() + start, n, labelCount, counts.data());
        EXPECT_EQ(counts, countedOneByOne(word.data() + start, n, labelCount))
            << labelCount << " labels, " << n << " modules from " << start;
      }
    }
  }
}

TEST(LabelCounts, OneLabelThroughoutIsCountedPastWhereAByteWraps) {
  const std::vector<uint8_t> word(40000, 2);
  uint64_t counts[3];
  countLabels(word.data(), word.size(), 3, counts);
  EXPECT_EQ(counts[0], 0u);
  EXPECT_EQ(counts[1], 0u);
  EXPECT_EQ(counts[2], 40000u);
}

}  // namespace
}  // namespace ontogen
