#include "core/parallel_for.h"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

#include <tbb/parallel_for.h>

namespace ontogen {

unsigned resolveThreadCount(unsigned requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

// The chunks are fixed by `count` and `threads` alone; oneTBB's persistent workers run
// them (no thread is made per call), at most as many at once as there are cores, and
// several worlds may call this at the same time from their own threads.
void parallelFor(size_t count, unsigned threads, const std::function<void(size_t, size_t, unsigned)>& body,
                 size_t grain) {
  const size_t workers =
      std::min<size_t>(std::max(1u, threads), std::max<size_t>(1, count / std::max<size_t>(1, grain)));
  if (workers <= 1) {
    body(0, count, 0);
    return;
  }
  std::vector<std::exception_ptr> errors(workers);
  tbb::parallel_for(size_t{0}, workers, [&](size_t worker) {
    const size_t begin = count * worker / workers, end = count * (worker + 1) / workers;
    try {
      body(begin, end, static_cast<unsigned>(worker));
    } catch (...) {
      errors[worker] = std::current_exception();
    }
  });
  // The first chunk's error wins, so the message does not depend on timing.
  for (auto& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace ontogen
