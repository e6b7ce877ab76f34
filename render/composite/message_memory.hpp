// Memory of the compositor's messages. A message is fresh memory every frame (a dense piece of a
// 2048 x 2048 image is 50 MB), so what it costs is mostly its page faults: on the development VM
// faulting in 4 KiB pages ran at 2.3 GB/s, slower than filling the message, against 19 GB/s on
// 2 MiB pages. A message of 2 MiB or more therefore gets a mapping of its own on huge pages,
// given back when it is freed. Not through malloc: glibc serves a freed size from its heap
// afterwards (its mmap threshold rises up to 32 MiB), whose regrown pages fault in 4 KiB again,
// and a run of composites became 3 times slower after a few frames.
//
// The words are left uninitialised when a message grows: the encoder and MPI_Recv write every
// word, so zeroing them first would only add a pass over memory.
#pragma once

#include <cstddef>
#include <new>
#include <utility>

namespace tetray::render {

// At least `bytes` bytes on a cache line; from 2 MiB on, a mapping of its own on huge pages where
// the system grants them. Throws std::bad_alloc.
void* allocate_message(std::size_t bytes);
// Frees what allocate_message(bytes) returned.
void free_message(void* p, std::size_t bytes) noexcept;

template <typename T>
struct MessageAllocator {
  using value_type = T;

  MessageAllocator() = default;
  template <typename U>
  explicit MessageAllocator(const MessageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_message(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_message(p, n * sizeof(T)); }

  // Default-initialised, which leaves a word as it was.
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  friend bool operator==(const MessageAllocator&, const MessageAllocator&) { return true; }
};

}  // namespace tetray::render
