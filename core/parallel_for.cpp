#include "core/parallel_for.h"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace ontogen {

unsigned resolveThreadCount(unsigned requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(size_t count, unsigned threads, const std::function<void(size_t, size_t, unsigned)>& body,
                 size_t grain) {
  const size_t workers =
      std::min<size_t>(std::max(1u, threads), std::max<size_t>(1, count / std::max<size_t>(1, grain)));
  if (workers <= 1) {
    body(0, count, 0);
    return;
  }
  std::vector<std::thread> pool;
  std::vector<std::exception_ptr> errors(workers);
  auto run = [&](size_t worker) {
    const size_t begin = count * worker / workers, end = count * (worker + 1) / workers;
    try {
      body(begin, end, static_cast<unsigned>(worker));
    } catch (...) {
      errors[worker] = std::current_exception();
    }
  };
  for (size_t worker = 1; worker < workers; ++worker) pool.emplace_back(run, worker);
  run(0);
  for (auto& thread : pool) thread.join();
  // The first chunk's error wins, so the message does not depend on timing.
  for (auto& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace ontogen
