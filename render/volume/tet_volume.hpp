// The renderer's own copy of one rank's tets: vertices as (x, y, z, f) floats relative to a
// double-precision local origin (meshes far from the origin keep float precision), and tets as
// 4 x int32 vertex indices. After a BVH build the tets are stored in leaf order, so a leaf is a
// contiguous range, and the vertices in the order the leaves first use them (Aman et al. 2022's
// point: neighbours in the tree are neighbours in memory), keeping only vertices some tet uses.
// `tet_ids` keeps each tet's id in the caller's numbering (the deterministic tie rule) and
// `point_vertex` the vertex each of the caller's points became (empty: the same index), so a
// new step's arrays are read in the caller's order and scattered into the store.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "render/core/large_array.hpp"
#include "render/core/vec.hpp"

namespace tetray::render {

struct alignas(16) Vertex {
  float x, y, z, f;
};

// point_vertex entry of a point that no tet uses.
inline constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

struct Tet {
  std::array<std::int32_t, 4> v;
};

struct TetVolume {
  Vec3d origin{};  // world = origin + local
  LargeArray<Vertex> vertices;
  LargeArray<std::uint32_t> point_vertex;  // vertex of the caller's point p, or kNoVertex
  LargeArray<Tet> tets;                    // in BVH leaf order once a BVH is built
  LargeArray<std::uint32_t> tet_ids;       // caller's id of tets[k]
  std::vector<float> color_field;          // optional per-vertex field to color by (empty: none)
  std::vector<Vec3f> gradients;            // per-vertex field gradient for smooth shading
                                           // (empty: flat shading only)

  std::size_t bytes() const {
    return vertices.capacity() * sizeof(Vertex) + tets.capacity() * sizeof(Tet) +
           (tet_ids.capacity() + point_vertex.capacity()) * sizeof(std::uint32_t) +
           color_field.capacity() * sizeof(float) + gradients.capacity() * sizeof(Vec3f);
  }
};

// The caller's point of every vertex (the inverse of point_vertex; the same index without it).
inline std::vector<std::size_t> vertex_points(const TetVolume& volume) {
  std::vector<std::size_t> point(volume.vertices.size());
  for (std::size_t v = 0; v < point.size(); ++v) point[v] = v;
  for (std::size_t p = 0; p < volume.point_vertex.size(); ++p) {
    if (volume.point_vertex[p] != kNoVertex) point[volume.point_vertex[p]] = p;
  }
  return point;
}

}  // namespace tetray::render
