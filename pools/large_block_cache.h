#pragma once
// The memory of the pools' big arrays, kept for reuse. A word of millions of cells is
// written into fresh memory, and fresh memory costs: the kernel zeroes every page on the
// first touch (on a virtual machine the host may have to back it first), a third of a
// large derivation's time. Blocks of 2 MiB and more are therefore not handed back when a
// word or a world lets them go: they wait here, up to a budget, for the next array of a
// similar size (the next step's word, the next run of a world in a sweep or a studio),
// which then starts on memory that is already mapped.
//
// Blocks of 2 MiB and more are aligned to 2 MiB and marked for transparent huge pages
// (madvise), which cuts the page faults 512-fold where the kernel allows it ("madvise" or
// "always"); elsewhere the hint is ignored. Blocks from 64 KiB up to 2 MiB are kept too,
// in sizes of powers of two: glibc maps such blocks of its own (past its mmap threshold)
// and unmaps them when they are freed, or trims them off the top of its heap, so the
// arrays of a word of some ten thousand to a few hundred thousand modules were faulted
// in again at every step (Koch to n = 10: 72 against 52 ms on one thread, 43 against 27
// on two). All functions are thread-safe.

#include <cstddef>
#include <cstdint>

namespace ontogen {

inline constexpr size_t kLargePageBytes = size_t{2} << 20;
/// The smallest block the cache keeps.
inline constexpr size_t kCachedBlockBytes = size_t{64} << 10;

/// The most bytes the cache keeps, beyond what is in use: 1 GiB.
inline constexpr uint64_t kLargeBlockCacheBytes = uint64_t{1} << 30;

/// A block of at least `bytes` (≥ kCachedBlockBytes): a kept one of a size between `bytes`
/// and twice it when there is one, else fresh memory; aligned to kLargePageBytes from that
/// size on, to 64 bytes below it. Throws std::bad_alloc (after giving back what the cache
/// held) when there is none.
void* acquireLargeBlock(size_t bytes);

/// Gives a block of acquireLargeBlock back, to be kept while the budget allows.
void releaseLargeBlock(void* block) noexcept;

/// Hands every kept block back to the system.
void trimLargeBlockCache() noexcept;

/// Keeps at most `bytes` from now on (never more than kLargeBlockCacheBytes), handing
/// back what is kept beyond: kept blocks are resident memory that no pool counts, so a
/// world under a memory limit keeps an eighth of it at most (core/world.cpp).
void limitLargeBlockCache(uint64_t bytes) noexcept;

struct LargeBlockCacheStats {
  uint64_t keptBytes = 0;  ///< held for reuse now
  uint64_t reused = 0;     ///< acquisitions served by a kept block
  uint64_t fresh = 0;      ///< acquisitions that took fresh memory
};
LargeBlockCacheStats largeBlockCacheStats() noexcept;

}  // namespace ontogen
