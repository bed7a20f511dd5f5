#pragma once
// An allocator for the pools' big arrays: blocks of 2 MiB and more come from, and go
// back to, the large block cache (pools/large_block_cache.h): aligned, marked for huge
// pages, and kept for the next array instead of being faulted in again.

#include <cstddef>
#include <new>

#include "pools/large_block_cache.h"

namespace ontogen {

template <class T>
class LargePageAllocator {
 public:
  using value_type = T;

  LargePageAllocator() noexcept = default;
  template <class U>
  LargePageAllocator(const LargePageAllocator<U>&) noexcept {}

  T* allocate(size_t count) {
    if (count > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const size_t bytes = count * sizeof(T);
    if (bytes < kLargePageBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(acquireLargeBlock(bytes));
  }

  void deallocate(T* block, size_t count) noexcept {
    if (count * sizeof(T) < kLargePageBytes)
      ::operator delete(block);
    else
      releaseLargeBlock(block);
  }

  template <class U>
  bool operator==(const LargePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace ontogen
