#pragma once
// An allocator for the pools' big arrays. A word of millions of cells is written once
// into fresh memory every step; with 4 KiB pages the kernel takes one fault per page.
// Blocks of 2 MiB and more are aligned to 2 MiB and marked for transparent huge pages
// (madvise), which cuts those faults 512-fold where the kernel allows it (the setting
// "madvise" or "always"); elsewhere the hint is ignored and nothing changes.

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace ontogen {

inline constexpr size_t kLargePageBytes = size_t{2} << 20;

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
    const size_t rounded = (bytes + kLargePageBytes - 1) / kLargePageBytes * kLargePageBytes;
    void* block = std::aligned_alloc(kLargePageBytes, rounded);
    if (!block) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    ::madvise(block, rounded, MADV_HUGEPAGE);  // a hint: failure leaves ordinary pages
#endif
    return static_cast<T*>(block);
  }

  void deallocate(T* block, size_t count) noexcept {
    if (count * sizeof(T) < kLargePageBytes)
      ::operator delete(block);
    else
      std::free(block);
  }

  template <class U>
  bool operator==(const LargePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace ontogen
