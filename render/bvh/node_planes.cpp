// The per-node linear fits of the level of detail (node_planes.hpp). A node's gradient g is the
// weighted mean of its parts' gradients (a leaf's parts are its tets, an inner node's its two
// children's planes), and its value at the box centre c the weighted mean of what each part
// predicts there along g: sum w (v + g . (c - p)) / W for a part of weight w, value v at point
// p. That is linear in the parts, so it is summed in one pass, and an inner node's fit equals the
// fit of all the tets below it.
#include "render/bvh/node_planes.hpp"

#include <tbb/parallel_for.h>

#include "render/volume/tet_gradient.hpp"

namespace tetray::render {
namespace {

Vec3d box_centre(const Bounds4& b) {
  return {0.5 * (double(b.lo[0]) + b.hi[0]), 0.5 * (double(b.lo[1]) + b.hi[1]),
          0.5 * (double(b.lo[2]) + b.hi[2])};
}

struct PlaneSum {
  Vec3d gradient{}, point{};  // weighted sums
  double value = 0, weight = 0;

  void add(const Vec3d& g_times_w, double v, const Vec3d& p, double w) {
    gradient = gradient + g_times_w;
    point = point + w * p;
    value += w * v;
    weight += w;
  }

  NodePlane plane(const Vec3d& centre) const {
    NodePlane out;
    if (weight <= 0) return out;
    const Vec3d g = (1 / weight) * gradient;
    out.gradient[0] = static_cast<float>(g.x);
    out.gradient[1] = static_cast<float>(g.y);
    out.gradient[2] = static_cast<float>(g.z);
    out.value = static_cast<float>((value + dot(g, weight * centre - point)) / weight);
    out.weight = static_cast<float>(weight);
    return out;
  }
};

NodePlane leaf_plane(const TetVolume& volume, const BvhNode& leaf) {
  PlaneSum sum;
  for (std::uint32_t t = leaf.first; t < leaf.first + leaf.count; ++t) {
    const Tet& tet = volume.tets[t];
    const WeightedGradient g = weighted_gradient(volume, tet);
    Vec3d centroid{};
    double value = 0;
    for (const std::int32_t k : tet.v) {
      centroid = centroid + 0.25 * to_vec3d(volume.vertices[k]);
      value += 0.25 * volume.vertices[k].f;
    }
    sum.add(g.gradient_times_weight, value, centroid, g.weight);
  }
  return sum.plane(box_centre(leaf.bounds));
}

NodePlane inner_plane(const Bvh& bvh, const std::vector<NodePlane>& planes, const BvhNode& node) {
  PlaneSum sum;
  for (std::uint32_t c = node.first; c < node.first + 2; ++c) {
    const NodePlane& p = planes[c];
    const Vec3d g{p.gradient[0], p.gradient[1], p.gradient[2]};
    sum.add(double(p.weight) * g, p.value, box_centre(bvh.nodes[c].bounds), p.weight);
  }
  return sum.plane(box_centre(node.bounds));
}

void fit_node(const TetVolume& volume, const Bvh& bvh, std::uint32_t i,
              std::vector<NodePlane>& planes) {
  const BvhNode& node = bvh.nodes[i];
  planes[i] = node.is_leaf() ? leaf_plane(volume, node) : inner_plane(bvh, planes, node);
}

}  // namespace

void fit_node_planes(const TetVolume& volume, const Bvh& bvh, std::vector<NodePlane>& planes) {
  planes.resize(bvh.nodes.size());
  if (bvh.empty()) return;
  // Children before parents, as the refit: within each subtree from its end, then the top.
  tbb::parallel_for(std::size_t{0}, bvh.subtrees.size(), [&](std::size_t s) {
    const Bvh::Subtree& st = bvh.subtrees[s];
    for (std::uint32_t i = st.end; i-- > st.begin;) fit_node(volume, bvh, i, planes);
    fit_node(volume, bvh, st.root, planes);
  });
  for (std::uint32_t i : bvh.top_nodes_bottom_up) fit_node(volume, bvh, i, planes);
}

}  // namespace tetray::render
