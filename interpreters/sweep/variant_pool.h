#pragma once
// Worker threads for the variants of a sweep: each worker takes the next index of a fixed
// list, runs it (one world, one thread) and queues what it gives back; the caller's
// thread takes the finished ones as they come, writes them and, across machines, sends
// them on. Which worker ran a variant, and when, changes nothing in its result.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace ontogen {

class VariantPool {
 public:
  /// What a worker does with one index: any text (a journal line); it must not throw.
  using Work = std::function<std::string(uint64_t)>;

  /// Starts `workers` threads (at least one) over `indices`, in order.
  VariantPool(unsigned workers, std::vector<uint64_t> indices, Work work);
  /// Stops taking indices and waits for the running ones.
  ~VariantPool();
  VariantPool(const VariantPool&) = delete;
  VariantPool& operator=(const VariantPool&) = delete;

  /// The variants finished since the last call, in the order they finished; waits up to
  /// `wait` when there are none yet.
  std::vector<std::pair<uint64_t, std::string>> take(std::chrono::milliseconds wait);
  /// No further index is started; the running ones finish.
  void stop();
  /// Every started variant has finished and been taken, and none is left to start
  /// (or stop() was called).
  bool done();

 private:
  void work();

  std::vector<uint64_t> indices_;
  Work work_;
  std::mutex mutex_;
  std::condition_variable finished_;
  size_t next_ = 0;      // the next index to start
  size_t running_ = 0;   // started and not finished
  bool stopped_ = false;
  std::deque<std::pair<uint64_t, std::string>> results_;
  std::vector<std::thread> threads_;
};

}  // namespace ontogen
