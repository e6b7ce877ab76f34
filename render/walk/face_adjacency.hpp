// Face adjacency of a rank's tets in the compact forms of Aman et al. 2022, §3. Both store the
// xor of a tet's four vertex indices, so a walk that knows the three vertices of the face it
// entered through recovers the fourth with three xors. Neighbours are indexed by the order of
// the vertex they lie across among the tet's four vertex indices sorted ascending (the
// paper's convention, which needs no per-tet vertex list):
// - Tet20 keeps the four neighbours (20 bytes a tet);
// - Tet16 keeps N_k xor N_3 for k < 3 (16 bytes), so a walk that knows the neighbour it came
//   from recovers any other with two xors.
// A face without a neighbour on this rank holds kBoundaryFace; a face of three or more tets and a
// tet with a repeated vertex are counted and treated as boundary. Built in parallel: every face is
// bucketed by its smallest vertex (atomic counts, a prefix sum, an atomic scatter), each bucket
// sorted whole and matched, so the result does not depend on the thread count. The adjacency
// depends on the topology and on the order of volume.tets only: a refit leaves it valid, a BVH
// rebuild (which reorders the tets) or a new topology needs a new one (docs/architecture.md §8).
// The tets stay in the BVH's leaf order, which already gives the locality of Aman et al.'s §5:
// their Hilbert order (hilbert_order.hpp) walked slower on the same rays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "render/volume/tet_volume.hpp"

namespace tetray::render {

inline constexpr std::uint32_t kBoundaryFace = std::numeric_limits<std::uint32_t>::max();

struct Tet20 {
  std::uint32_t vertex_xor;
  std::uint32_t neighbor[4];

  std::uint32_t next(std::uint32_t /*previous*/, int /*order_in*/, int order_out) const {
    return neighbor[order_out];
  }
};

struct Tet16 {
  std::uint32_t vertex_xor;
  std::uint32_t neighbor_xor[3];  // N_k xor N_3

  // The neighbour across the vertex of order `order_out`, knowing that `previous` lies across
  // the vertex of order `order_in` (Aman et al. 2022, Algorithm 7).
  std::uint32_t next(std::uint32_t previous, int order_in, int order_out) const {
    std::uint32_t n = previous;
    if (order_in != 3) n ^= neighbor_xor[order_in];
    if (order_out != 3) n ^= neighbor_xor[order_out];
    return n;
  }
};

static_assert(sizeof(Tet20) == 20 && sizeof(Tet16) == 16);

// A face of the domain's boundary on this rank: tet `tet`'s face opposite its local vertex
// `opposite` (an index into Tet::v).
struct BoundaryFaceRef {
  std::uint32_t tet;
  std::uint32_t opposite;
};

template <typename Layout>
struct FaceAdjacency {
  std::vector<Layout> tets;  // parallel to TetVolume::tets
  std::vector<BoundaryFaceRef> boundary;
  std::uint64_t nonmanifold_faces = 0;  // faces of more than two tets, treated as boundary
  std::uint64_t degenerate_tets = 0;    // a repeated vertex index: never entered

  std::size_t bytes() const {
    return tets.capacity() * sizeof(Layout) + boundary.capacity() * sizeof(BoundaryFaceRef);
  }
};

// Order of vertex index `x` among a tet's four distinct vertex indices `v` (0: the smallest).
inline int vertex_order(std::uint32_t x, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return int(a < x) + int(b < x) + int(c < x);
}

// Builds the adjacency of volume.tets in parallel (oneTBB, in the calling arena): the faces are
// bucketed by their smallest vertex and matched inside each bucket, so the result does not
// depend on the thread count. Tets must number fewer than 2^30.
template <typename Layout>
FaceAdjacency<Layout> build_face_adjacency(const TetVolume& volume);

extern template FaceAdjacency<Tet20> build_face_adjacency<Tet20>(const TetVolume&);
extern template FaceAdjacency<Tet16> build_face_adjacency<Tet16>(const TetVolume&);

}  // namespace tetray::render
