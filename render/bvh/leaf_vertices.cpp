#include "render/bvh/leaf_vertices.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace tetray::render {
namespace {

constexpr std::size_t kNodesPerBlock = 2048;

// One block of nodes: each leaf's distinct vertices, concatenated, and per node their count
// (counts[i] for node i).
// `seen[v]` holds the last leaf (node index + 1) that listed vertex v, so a vertex shared by
// several tets of a leaf is listed once without sorting.
void list_block(const TetVolume& volume, const Bvh& bvh, std::size_t first, std::size_t last,
                std::vector<std::uint32_t>& seen, std::uint32_t* counts,
                std::vector<std::uint32_t>& out) {
  std::size_t corners = 0;
  for (std::size_t i = first; i < last; ++i) corners += 4 * std::size_t{bvh.nodes[i].count};
  out.resize(corners);
  std::size_t listed = 0;
  for (std::size_t i = first; i < last; ++i) {
    const BvhNode& node = bvh.nodes[i];
    if (!node.is_leaf()) continue;
    const auto stamp = static_cast<std::uint32_t>(i + 1);
    const std::size_t before = listed;
    // Branch-free: whether a corner is new is data, not control flow (about a quarter are).
    for (std::uint32_t t = node.first; t < node.first + node.count; ++t)
      for (std::int32_t v : volume.tets[t].v) {
        out[listed] = static_cast<std::uint32_t>(v);
        listed += seen[v] != stamp;
        seen[v] = stamp;
      }
    counts[i] = static_cast<std::uint32_t>(listed - before);
  }
  out.resize(listed);
}

}  // namespace

void list_leaf_vertices(const TetVolume& volume, Bvh& bvh) {
  const std::size_t nodes = bvh.nodes.size();
  const std::size_t blocks = (nodes + kNodesPerBlock - 1) / kNodesPerBlock;
  std::vector<std::vector<std::uint32_t>> lists(blocks);
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> seen_per_thread(
      [&] { return std::vector<std::uint32_t>(volume.vertices.size(), 0); });
  // Node i's count goes to leaf_vertex_begin[i + 1]; the running sum then makes the offsets.
  bvh.leaf_vertex_begin.assign(nodes + 1, 0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t first = b * kNodesPerBlock;
    list_block(volume, bvh, first, std::min(nodes, first + kNodesPerBlock), seen_per_thread.local(),
               bvh.leaf_vertex_begin.data() + 1, lists[b]);
  });
  std::partial_sum(bvh.leaf_vertex_begin.begin(), bvh.leaf_vertex_begin.end(),
                   bvh.leaf_vertex_begin.begin());
  bvh.leaf_vertices.resize(bvh.leaf_vertex_begin[nodes]);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    std::copy(lists[b].begin(), lists[b].end(),
              bvh.leaf_vertices.begin() + bvh.leaf_vertex_begin[b * kNodesPerBlock]);
  });
}

}  // namespace tetray::render
