// A fixed, platform-independent 64-bit mix (the finaliser of splitmix64): the same bits on every
// machine and rank, for deterministic jitter and for keys that must not depend on the partition.
#pragma once

#include <bit>
#include <cstdint>

namespace tetray::render {

inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// A hash of a point's position, the same wherever the point is held (-0 and +0 alike): an order
// of points, or a key of what they make, that does not depend on how a mesh is numbered.
inline std::uint64_t position_hash(double x, double y, double z) {
  std::uint64_t h = 0;
  for (double c : {x, y, z}) h = mix64(h ^ std::bit_cast<std::uint64_t>(c == 0 ? 0.0 : c));
  return h;
}

}  // namespace tetray::render
