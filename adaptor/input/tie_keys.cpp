#include "adaptor/input/tie_keys.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "render/core/framebuffer.hpp"
#include "render/core/hash.hpp"

namespace tetray {
namespace {

using render::mix64;

template <typename T>
std::uint64_t corner_hash(const T* xyz, std::size_t point_count, std::int64_t index) {
  if (index < 0 || static_cast<std::uint64_t>(index) >= point_count) {
    return mix64(static_cast<std::uint64_t>(index));
  }
  const T* p = &xyz[3 * index];
  return render::position_hash(p[0], p[1], p[2]);
}

// The same key whatever the order of the tet's corners; never the background's kNoHit.
template <typename T>
std::uint32_t position_key(const T* xyz, std::size_t point_count, const std::int64_t* corners) {
  std::array<std::uint64_t, 4> hashes;
  for (int c = 0; c < 4; ++c) hashes[c] = corner_hash(xyz, point_count, corners[c]);
  std::sort(hashes.begin(), hashes.end());
  std::uint64_t h = 0;
  for (std::uint64_t corner : hashes) h = mix64(h ^ corner);
  const auto key = static_cast<std::uint32_t>(h ^ (h >> 32));
  return key == render::kNoHit ? key - 1 : key;
}

template <typename T>
void position_keys(const T* xyz, std::size_t point_count, std::span<const std::int64_t> tets,
                   std::vector<std::uint32_t>& keys) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keys.size()), [&](const auto& range) {
    for (std::size_t t = range.begin(); t < range.end(); ++t) {
      keys[t] = position_key(xyz, point_count, &tets[4 * t]);
    }
  });
}

}  // namespace

std::string tie_keys(const TetsView& tets, std::span<const std::int64_t> connectivity,
                     const PointsView& points, std::vector<std::uint32_t>& keys) {
  keys.resize(tets.count);
  if (tets.global_ids == nullptr) {
    if (points.type == ScalarType::float32) {
      position_keys(static_cast<const float*>(points.xyz), points.count, connectivity, keys);
    } else {
      position_keys(static_cast<const double*>(points.xyz), points.count, connectivity, keys);
    }
    return {};
  }
  for (std::size_t t = 0; t < tets.count; ++t) {
    const std::int64_t id = tets.global_ids[t];
    if (id < 0 || id >= static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max())) {
      return "mesh.tets.global_ids[" + std::to_string(t) + "] = " + std::to_string(id) +
             " is outside [0, 2^32-1)";
    }
    keys[t] = static_cast<std::uint32_t>(id);
  }
  return {};
}

}  // namespace tetray
