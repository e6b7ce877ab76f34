// Arrays a frame reads in an order the hardware cannot predict (the tets, vertices, tet ids and
// BVH nodes a tile's leaves point to, and the image rows a tile writes): at millions of tets
// they span hundreds of MB, and with 4 KiB pages nearly every leaf a tile reaches costs a TLB
// miss and a page walk besides its cache misses (at 14M tets the exact frame took about 16%
// longer on 4 KiB pages than on 2 MiB ones, the same image). An allocation of at least 2 MiB is
// aligned to 2 MiB and asks Linux for transparent huge pages (madvise) before any of its pages is
// touched: the kernel's default mode ("madvise") grants them to whoever asks, as Embree asks for
// its own buffers. Where they are refused or unknown, the pages are the usual ones; nothing else
// changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tetray::render {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;
// Every array starts on a cache line (the framebuffer's streaming stores need it).
inline constexpr std::size_t kCacheLine = 64;

inline void* allocate_large(std::size_t bytes) {
  if (bytes < kHugePage) return ::operator new(bytes, std::align_val_t(kCacheLine));
  if (bytes > std::size_t(PTRDIFF_MAX) - kHugePage) throw std::bad_alloc();
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (p == nullptr) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: a refusal leaves the usual pages
#endif
  return p;
}

inline void free_large(void* p, std::size_t bytes) noexcept {
  if (bytes < kHugePage) return ::operator delete(p, std::align_val_t(kCacheLine));
  std::free(p);
}

template <typename T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <typename U>
  explicit HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    static_assert(alignof(T) <= kCacheLine);
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_large(p, n * sizeof(T)); }

  friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

template <typename T>
using LargeArray = std::vector<T, HugePageAllocator<T>>;

}  // namespace tetray::render
