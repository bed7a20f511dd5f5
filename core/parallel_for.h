#pragma once
// Splits a loop over cells into contiguous chunks, one per thread, run by oneTBB's
// persistent workers. The chunks depend on the thread count, so a body must make each
// element's result independent of the others (read a snapshot, write its own slot);
// then one thread and many give the same bits. A worker index is a chunk index: what a
// body keeps per worker is kept per chunk.

#include <cstddef>
#include <functional>

namespace ontogen {

/// Threads to use when the user asked for `requested` (0: all cores).
unsigned resolveThreadCount(unsigned requested);

/// Runs body(begin, end, worker) over [0, count) in `threads` chunks; small loops (fewer
/// than `grain` elements per thread) run on the calling thread alone.
void parallelFor(size_t count, unsigned threads, const std::function<void(size_t, size_t, unsigned)>& body,
                 size_t grain = 4096);

}  // namespace ontogen
