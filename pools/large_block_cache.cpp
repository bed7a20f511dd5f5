#include "pools/large_block_cache.h"

#include <algorithm>
#include <bit>
#include <iterator>
#include <cstdlib>
#include <map>
#include <mutex>
#include <new>
#include <unordered_map>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ontogen {

namespace {

// glibc's default mmap threshold (and trim threshold), 128 KiB.
constexpr int kGlibcMmapThreshold = 128 << 10;

struct Cache {
  std::mutex mutex;
  std::multimap<size_t, void*> kept;        // size → block, waiting for reuse
  std::unordered_map<void*, size_t> inUse;  // block → its size, handed out
  uint64_t keptBytes = 0;
  uint64_t budget = kLargeBlockCacheBytes;  // limitLargeBlockCache
  uint64_t reused = 0;
  uint64_t fresh = 0;
};

// Never destroyed: arrays of static objects may give their blocks back after main().
Cache& cache() {
  static Cache* instance = new Cache;
  return *instance;
}

void freeKept(Cache& state) {
  for (auto& [size, block] : state.kept) std::free(block);
  state.kept.clear();
  state.keptBytes = 0;
}

void* freshBlock(size_t rounded) {
  if (rounded < kLargePageBytes) return std::aligned_alloc(64, rounded);
  void* block = std::aligned_alloc(kLargePageBytes, rounded);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (block) ::madvise(block, rounded, MADV_HUGEPAGE);  // a hint: failure leaves ordinary pages
#endif
  return block;
}

}  // namespace

void* acquireLargeBlock(size_t bytes) {
  // Whole large pages from 2 MiB on, a power of two below.
  const size_t rounded = bytes >= kLargePageBytes ? (bytes + kLargePageBytes - 1) / kLargePageBytes * kLargePageBytes
                                                  : std::bit_ceil(std::max(bytes, kCachedBlockBytes));
  Cache& state = cache();
  std::lock_guard lock(state.mutex);
  // The smallest kept block that fits, if it wastes at most half of itself.
  if (auto fit = state.kept.lower_bound(rounded); fit != state.kept.end() && fit->first / 2 <= rounded) {
    void* block = fit->second;
    state.inUse.emplace(block, fit->first);
    state.keptBytes -= fit->first;
    state.kept.erase(fit);
    ++state.reused;
    return block;
  }
  // No kept block fits: the kept blocks smaller than this one are of sizes a growing word
  // has left behind, and would only add to the peak (Koch to n = 10 kept 5 MiB of them).
  // The next run of a world finds its blocks kept, and takes none fresh.
  while (!state.kept.empty() && state.kept.begin()->first < rounded) {
    std::free(state.kept.begin()->second);
    state.keptBytes -= state.kept.begin()->first;
    state.kept.erase(state.kept.begin());
  }
  void* block = freshBlock(rounded);
  if (!block && !state.kept.empty()) {
    freeKept(state);
    block = freshBlock(rounded);
  }
  if (!block) throw std::bad_alloc();
  state.inUse.emplace(block, rounded);
  ++state.fresh;
  return block;
}

void releaseLargeBlock(void* block) noexcept {
  if (!block) return;
  Cache& state = cache();
  std::lock_guard lock(state.mutex);
  const auto found = state.inUse.find(block);
  if (found == state.inUse.end()) return std::free(block);  // not ours: cannot happen
  const size_t size = found->second;
  state.inUse.erase(found);
  // Over budget: the smallest kept blocks go first, the largest are the costliest to fault in.
  while (state.keptBytes + size > state.budget && !state.kept.empty() && state.kept.begin()->first <= size) {
    std::free(state.kept.begin()->second);
    state.keptBytes -= state.kept.begin()->first;
    state.kept.erase(state.kept.begin());
  }
  if (state.keptBytes + size > state.budget) return std::free(block);
  state.kept.emplace(size, block);
  state.keptBytes += size;
}

void trimLargeBlockCache() noexcept {
  Cache& state = cache();
  std::lock_guard lock(state.mutex);
  freeKept(state);
}

void limitLargeBlockCache(uint64_t bytes) noexcept {
#if defined(__GLIBC__)
  // glibc raises its mmap threshold to the size of each mapped block freed (up to 32 MiB)
  // and then keeps up to twice that of freed memory at the top of its heap: resident
  // memory that no pool counts (a colony under a limit of 100 MiB peaked at 132 MiB, 96
  // with the threshold fixed). Setting it fixes it at glibc's own first value.
  mallopt(M_MMAP_THRESHOLD, kGlibcMmapThreshold);
#endif
  Cache& state = cache();
  std::lock_guard lock(state.mutex);
  state.budget = std::min(state.budget, bytes);
  // The largest go first: the fewest blocks to free.
  while (state.keptBytes > state.budget && !state.kept.empty()) {
    const auto largest = std::prev(state.kept.end());
    std::free(largest->second);
    state.keptBytes -= largest->first;
    state.kept.erase(largest);
  }
}

LargeBlockCacheStats largeBlockCacheStats() noexcept {
  Cache& state = cache();
  std::lock_guard lock(state.mutex);
  return {state.keptBytes, state.reused, state.fresh};
}

}  // namespace ontogen
