#include "render/walk/hilbert_order.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace tetray::render {

std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits) {
  std::uint32_t p[3] = {x, y, z};
  const std::uint32_t top = 1u << (bits - 1);
  for (std::uint32_t q = top; q > 1; q >>= 1) {  // undo the excess work of the inverse
    const std::uint32_t mask = q - 1;
    for (std::uint32_t& c : p) {
      if (c & q) {
        p[0] ^= mask;  // invert
      } else {
        const std::uint32_t t = (p[0] ^ c) & mask;  // exchange
        p[0] ^= t;
        c ^= t;
      }
    }
  }
  p[1] ^= p[0];  // Gray encode
  p[2] ^= p[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1)
    if (p[2] & q) t ^= q - 1;
  for (std::uint32_t& c : p) c ^= t;
  std::uint64_t index = 0;
  for (int bit = bits - 1; bit >= 0; --bit)
    for (const std::uint32_t c : p) index = (index << 1) | ((c >> bit) & 1u);
  return index;
}

namespace {

constexpr int kBits = 21;

std::vector<std::uint64_t> centroid_keys(const TetVolume& volume) {
  Vec3f lo{volume.vertices[0].x, volume.vertices[0].y, volume.vertices[0].z}, hi = lo;
  for (const Vertex& v : volume.vertices) {
    lo = min(lo, Vec3f{v.x, v.y, v.z});
    hi = max(hi, Vec3f{v.x, v.y, v.z});
  }
  const double cells = double(1u << kBits) - 1;
  std::vector<std::uint64_t> keys(volume.tets.size());
  tbb::parallel_for(std::size_t{0}, keys.size(), [&](std::size_t t) {
    std::uint32_t grid[3];
    for (int a = 0; a < 3; ++a) {
      double centroid = 0;
      for (const std::int32_t k : volume.tets[t].v) {
        const Vertex& v = volume.vertices[k];
        centroid += 0.25 * (a == 0 ? v.x : a == 1 ? v.y : v.z);
      }
      const double extent = double(hi[a]) - lo[a];
      const double unit = extent > 0 ? (centroid - lo[a]) / extent : 0;
      grid[a] = static_cast<std::uint32_t>(std::clamp(unit, 0.0, 1.0) * cells);
    }
    keys[t] = hilbert_index(grid[0], grid[1], grid[2], kBits);
  });
  return keys;
}

}  // namespace

TetVolume hilbert_ordered(const TetVolume& volume) {
  TetVolume out;
  out.origin = volume.origin;
  if (volume.tets.empty()) return out;
  const std::vector<std::uint64_t> keys = centroid_keys(volume);
  std::vector<std::uint32_t> order(volume.tets.size());
  std::iota(order.begin(), order.end(), 0u);
  tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  LargeArray<std::uint32_t> renumber(volume.vertices.size(), kNoVertex);
  const bool gradients = volume.gradients.size() == volume.vertices.size();
  const bool colors = volume.color_field.size() == volume.vertices.size();
  for (const std::uint32_t t : order) {
    Tet tet = volume.tets[t];
    for (std::int32_t& k : tet.v) {
      std::uint32_t& to = renumber[static_cast<std::size_t>(k)];
      if (to == kNoVertex) {
        to = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(volume.vertices[k]);
        if (gradients) out.gradients.push_back(volume.gradients[k]);
        if (colors) out.color_field.push_back(volume.color_field[k]);
      }
      k = static_cast<std::int32_t>(to);
    }
    out.tets.push_back(tet);
    out.tet_ids.push_back(volume.tet_ids[t]);
  }
  // An empty point_vertex means point p is vertex p: after renumbering it no longer is.
  out.point_vertex = volume.point_vertex.empty() ? renumber : volume.point_vertex;
  if (!volume.point_vertex.empty()) {
    for (std::uint32_t& v : out.point_vertex)
      if (v != kNoVertex) v = renumber[v];
  }
  return out;
}

}  // namespace tetray::render
