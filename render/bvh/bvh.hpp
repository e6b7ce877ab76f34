// The implicit 4D min/max BVH of Wald et al. 2007, §5: every node bounds x, y, z and the scalar
// range of the tets below it, so a subtree whose range misses every isovalue is culled before any
// geometric test, for all isovalues at once. Children of an inner node are stored next to each
// other; a leaf holds a contiguous range of TetVolume::tets (the build reorders the tets into leaf
// order and renumbers the vertices in the order the leaves first use them, the reordering for
// locality of Aman et al. 2022, §5, along the BVH's own order). Two builders: a BIH-style spatial
// median (the default) and a binned SAH; the top levels are split breadth-first in parallel down
// to about 64 subtrees, then built in parallel; the tree depends only on the data, never on the
// thread count. A node is 40 bytes; with leaves of up to 64 tets (the default) the BVH, its leaf
// vertex lists and the tet ids take about 8.5 bytes per tet (16 with leaves of 16). Large leaves
// cost the tiled frame nothing measurable while a new step's refit, whose cost follows the nodes,
// takes about half as long; a capped frame, which locates a point per cap pixel one tet at a time,
// is 1.24x slower with them, so a field with a clip cap gets leaves of 16 by default. A new step
// refits the recorded subtrees in parallel, each depth first (leaves, their vertex lists and the
// vertices read front to back), then the nodes above them; the refit's SAH cost against the
// build's decides a rebuild (render/update/volume_update.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "render/volume/tet_volume.hpp"

namespace tetray::render {

struct Bounds4 {
  float lo[4];  // x, y, z, f minimum
  float hi[4];  // x, y, z, f maximum
};

struct BvhNode {
  Bounds4 bounds;
  std::uint32_t first;  // inner: index of the first child (the second is first + 1);
                        // leaf: index of the first tet
  std::uint32_t count;  // leaf: number of tets (>= 1); inner: 0

  bool is_leaf() const { return count != 0; }
};

// The linear fit of the field over a node's vertices, for the level of detail
// (node_planes.hpp).
struct NodePlane {
  float gradient[3] = {0, 0, 0};  // the fit's field gradient (local units); zero: no fit
  float value = 0;                // the fit's field value at the centre of the node's box

  bool flat() const { return gradient[0] == 0 && gradient[1] == 0 && gradient[2] == 0; }
};

enum class BvhBuilder { bih, sah };

struct BvhBuildOptions {
  BvhBuilder builder = BvhBuilder::bih;
  // Maximum tets per leaf. A refit's cost follows the nodes, and the tiled frame tests a leaf's
  // tets lanewise, so large leaves cost the frame nothing measurable while the refit of a new
  // step takes about half as long as with 16 (README, "Performance"); locating points per pixel
  // (a clip cap) tests a leaf's tets one by one and prefers kPointLocationLeafSize. Taken within
  // 1..kMaxLeafSize.
  int leaf_size = 64;
};

// The most tets a leaf holds, whatever leaf_size asks: the tiled frame keeps which of a leaf's
// tets straddle an isovalue as the bits of one word (render/trace/leaf_straddles.hpp).
inline constexpr int kMaxLeafSize = 64;

// Leaves for a BVH that locates points per pixel (a clip cap, render/walk/clip_cap.hpp).
inline constexpr int kPointLocationLeafSize = 16;

struct Bvh {
  LargeArray<BvhNode> nodes;  // nodes[0] is the root (absent for an empty volume)
  // Subtrees recorded at build time for parallel refit (Wald et al. 2007, §6.2): each subtree's
  // root sits among the top nodes, the rest of it in nodes [begin, end), children after parents.
  struct Subtree {
    std::uint32_t root, begin, end;
  };
  std::vector<Subtree> subtrees;
  std::vector<std::uint32_t> top_nodes_bottom_up;  // inner nodes above the subtrees
  // The distinct vertices of each leaf's tets, read by the refit (leaf_vertices.hpp): node i's
  // are leaf_vertices[leaf_vertex_begin[i], leaf_vertex_begin[i + 1]), none for inner nodes.
  std::vector<std::uint32_t> leaf_vertex_begin;
  LargeArray<std::uint32_t> leaf_vertices;
  // SAH cost (traversal and tet cost 1, normalised by the root's surface area) at the last
  // build and after the last refit: the quality measure of the rebuild policy.
  double sah_cost_at_build = 0;
  double sah_cost_now = 0;
  // Per node, the linear fit of the field for the level of detail (node_planes.hpp); empty
  // unless a scene asks for it.
  std::vector<NodePlane> lod_planes;

  bool empty() const { return nodes.empty(); }
  std::size_t bytes() const {
    return nodes.capacity() * sizeof(BvhNode) +
           (leaf_vertex_begin.capacity() + leaf_vertices.capacity()) * sizeof(std::uint32_t) +
           lod_planes.capacity() * sizeof(NodePlane);
  }
};

// Builds the BVH over volume.tets and reorders volume.tets and volume.tet_ids into leaf order,
// then fits the node bounds (refit_bvh). The tree and its layout depend only on the data, not
// on the thread count. Parallel with oneTBB within the calling task arena.
Bvh build_bvh(TetVolume& volume, const BvhBuildOptions& options);

// Refits from the vertex store as it is: all 4D bounds (geometry = true) or only the scalar
// ranges. Parallel over the recorded subtrees, then the top nodes; bitwise independent of the
// thread count. Updates sah_cost_now when geometry changes.
void refit_bvh(const TetVolume& volume, Bvh& bvh, bool geometry);

}  // namespace tetray::render
