// The large block cache: a block given back is handed out again for an array of a
// similar size, not for one less than half its size, and the cache keeps no more than
// its budget.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "pools/large_block_cache.h"
#include "pools/pool.h"

namespace ontogen {
namespace {

constexpr size_t kMiB = size_t{1} << 20;

TEST(LargeBlockCache, ABlockGivenBackServesTheNextArrayOfASimilarSize) {
  trimLargeBlockCache();
  const LargeBlockCacheStats before = largeBlockCacheStats();
  void* first = acquireLargeBlock(10 * kMiB);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(first) % kLargePageBytes, 0u);
  releaseLargeBlock(first);
  EXPECT_EQ(largeBlockCacheStats().keptBytes, 10 * kMiB);
  void* second = acquireLargeBlock(7 * kMiB);  // fits, wasting less than half
  EXPECT_EQ(second, first);
  EXPECT_EQ(largeBlockCacheStats().reused, before.reused + 1);
  EXPECT_EQ(largeBlockCacheStats().keptBytes, 0u);
  releaseLargeBlock(second);
  void* small = acquireLargeBlock(4 * kMiB);  // the 10 MiB block would waste more than half
  EXPECT_NE(small, first);
  EXPECT_EQ(largeBlockCacheStats().fresh, before.fresh + 2);
  releaseLargeBlock(small);
  trimLargeBlockCache();
  EXPECT_EQ(largeBlockCacheStats().keptBytes, 0u);
}

// Blocks below 2 MiB, which glibc would map and unmap each time, are kept in powers of
// two: a 300 KiB block is 512 KiB, and serves the next array of 256 to 512 KiB.
TEST(LargeBlockCache, AMidSizeBlockGivenBackServesTheNextArrayOfASimilarSize) {
  trimLargeBlockCache();
  const LargeBlockCacheStats before = largeBlockCacheStats();
  void* first = acquireLargeBlock(300 << 10);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(first) % 64, 0u);
  releaseLargeBlock(first);
  EXPECT_EQ(largeBlockCacheStats().keptBytes, size_t{512} << 10);
  void* second = acquireLargeBlock(400 << 10);
  EXPECT_EQ(second, first);
  releaseLargeBlock(second);
  void* smaller = acquireLargeBlock(100 << 10);  // 128 KiB: the kept block would waste too much
  EXPECT_NE(smaller, first);
  EXPECT_EQ(largeBlockCacheStats().reused, before.reused + 1);
  EXPECT_EQ(largeBlockCacheStats().fresh, before.fresh + 2);
  releaseLargeBlock(smaller);
  // A fresh block gives back the kept ones smaller than itself: sizes a growing word has
  // left behind (the 512 KiB and 128 KiB blocks), not the peak's.
  EXPECT_EQ(largeBlockCacheStats().keptBytes, size_t{640} << 10);
  void* large = acquireLargeBlock(4 * kMiB);
  EXPECT_EQ(largeBlockCacheStats().keptBytes, 0u);
  releaseLargeBlock(large);
  trimLargeBlockCache();
}

TEST(LargeBlockCache, KeepsNoMoreThanItsBudget) {
  trimLargeBlockCache();
  // Blocks that are never touched cost address space only.
  std::vector<void*> blocks;
  for (int i = 0; i < 5; ++i) blocks.push_back(acquireLargeBlock(300 * kMiB));
  for (void* block : blocks) releaseLargeBlock(block);
  EXPECT_LE(largeBlockCacheStats().keptBytes, kLargeBlockCacheBytes);
  EXPECT_EQ(largeBlockCacheStats().keptBytes, 3 * 300 * kMiB);
  trimLargeBlockCache();
}

TEST(LargeBlockCache, TheNextWorldsArraysReuseTheLastOnesMemory) {
  trimLargeBlockCache();
  const CellRecord* firstData = nullptr;
  {
    CellArray cells(1'000'000);  // 24 MB
    firstData = cells.data();
  }
  CellArray again(900'000);
  EXPECT_EQ(again.data(), firstData);
  CellArray small(1000);  // below the block size: ordinary memory
  EXPECT_NE(small.data(), firstData);
  const CellRecord* midData = nullptr;
  {
    CellArray mid(20'000);  // 480 KB: kept as a block of 512 KiB
    midData = mid.data();
  }
  CellArray midAgain(15'000);
  EXPECT_EQ(midAgain.data(), midData);
}

}  // namespace
}  // namespace ontogen
