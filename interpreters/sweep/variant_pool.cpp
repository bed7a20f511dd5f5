#include "interpreters/sweep/variant_pool.h"

#include <algorithm>

namespace ontogen {

VariantPool::VariantPool(unsigned workers, std::vector<uint64_t> indices, Work work)
    : indices_(std::move(indices)), work_(std::move(work)) {
  const size_t count = std::clamp<size_t>(workers, 1, std::max<size_t>(1, indices_.size()));
  for (size_t i = 0; i < count; ++i) threads_.emplace_back([this] { this->work(); });
}

VariantPool::~VariantPool() {
  stop();
  for (std::thread& thread : threads_) thread.join();
}

void VariantPool::work() {
  for (;;) {
    uint64_t index = 0;
    {
      std::lock_guard lock(mutex_);
      if (stopped_ || next_ >= indices_.size()) return;
      index = indices_[next_++];
      ++running_;
    }
    std::string result = work_(index);
    {
      std::lock_guard lock(mutex_);
      results_.emplace_back(index, std::move(result));
      --running_;
    }
    finished_.notify_all();
  }
}

std::vector<std::pair<uint64_t, std::string>> VariantPool::take(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  finished_.wait_for(lock, wait, [this] { return !results_.empty(); });
  std::vector<std::pair<uint64_t, std::string>> taken(std::make_move_iterator(results_.begin()),
                                                      std::make_move_iterator(results_.end()));
  results_.clear();
  return taken;
}

void VariantPool::stop() {
  std::lock_guard lock(mutex_);
  stopped_ = true;
}

bool VariantPool::done() {
  std::lock_guard lock(mutex_);
  return running_ == 0 && results_.empty() && (stopped_ || next_ >= indices_.size());
}

}  // namespace ontogen
