// A fixed, platform-independent 64-bit mix (the finaliser of splitmix64): the same bits on every
// machine and rank, for deterministic jitter and for keys that must not depend on the partition.
#pragma once

#include <cstdint>

namespace tetray::render {

inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace tetray::render
