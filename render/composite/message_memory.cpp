#include "render/composite/message_memory.hpp"

#include <cstdint>

#include "render/core/large_array.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tetray::render {
namespace {

std::size_t huge_pages_of(std::size_t bytes) {
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

}  // namespace

#if defined(__linux__)

// A mapping one huge page longer than needed, cut down to the 2 MiB-aligned part, so that every
// page of it can be a huge one.
void* allocate_message(std::size_t bytes) {
  if (bytes < kHugePage) return ::operator new(bytes, std::align_val_t(kCacheLine));
  if (bytes > std::size_t(PTRDIFF_MAX) - 2 * kHugePage) throw std::bad_alloc();
  const std::size_t length = huge_pages_of(bytes);
  void* mapped =
      mmap(nullptr, length + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto address = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = (address + kHugePage - 1) / kHugePage * kHugePage;
  const std::uintptr_t head = aligned - address;  // below one huge page, so the tail is not empty
  if (head > 0) munmap(mapped, head);
  munmap(reinterpret_cast<void*>(aligned + length), kHugePage - head);
  auto* start = reinterpret_cast<void*>(aligned);
  madvise(start, length, MADV_HUGEPAGE);  // advice only: a refusal leaves the usual pages
  return start;
}

void free_message(void* p, std::size_t bytes) noexcept {
  if (bytes < kHugePage) return ::operator delete(p, std::align_val_t(kCacheLine));
  munmap(p, huge_pages_of(bytes));
}

#else

void* allocate_message(std::size_t bytes) { return allocate_large(bytes); }
void free_message(void* p, std::size_t bytes) noexcept { free_large(p, bytes); }

#endif

}  // namespace tetray::render
