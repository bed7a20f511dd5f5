#pragma once
// An allocator for the pools' big arrays: blocks of 64 KiB and more come from, and go
// back to, the large block cache (pools/large_block_cache.h): aligned, from 2 MiB on
// marked for huge pages, and kept for the next array instead of being faulted in again.

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "pools/large_block_cache.h"

namespace ontogen {

namespace detail {
// Set by resizeForOverwrite while it grows an array: new elements are left unwritten.
inline thread_local bool leaveNewElementsUnwritten = false;
}  // namespace detail

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
    if (bytes < kCachedBlockBytes) return static_cast<T*>(::operator new(bytes));
    return static_cast<T*>(acquireLargeBlock(bytes));
  }

  void deallocate(T* block, size_t count) noexcept {
    if (count * sizeof(T) < kCachedBlockBytes)
      ::operator delete(block);
    else
      releaseLargeBlock(block);
  }

  /// Value-initialises a new element, unless resizeForOverwrite is growing the array.
  template <class U>
  void construct(U* element) noexcept(std::is_nothrow_default_constructible_v<U>) {
    if (!detail::leaveNewElementsUnwritten) ::new (static_cast<void*>(element)) U();
  }
  template <class U, class... Args>
  void construct(U* element, Args&&... args) {
    ::new (static_cast<void*>(element)) U(std::forward<Args>(args)...);
  }

  template <class U>
  bool operator==(const LargePageAllocator<U>&) const noexcept {
    return true;
  }
};

/// A vector whose large buffers come from the large block cache.
template <class T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

/// Grows `array` to `size` elements without writing the new ones (no pass over fresh
/// memory before the real one), for a caller that writes every one of them next, each
/// thread its own slice. Elements already there are kept.
template <class T>
void resizeForOverwrite(std::vector<T, LargePageAllocator<T>>& array, size_t size) {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  struct Restore {
    ~Restore() { detail::leaveNewElementsUnwritten = false; }
  } restore;
  detail::leaveNewElementsUnwritten = true;
  array.resize(size);
}

}  // namespace ontogen
