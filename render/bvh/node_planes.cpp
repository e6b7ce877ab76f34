// The per-node linear fits of the level of detail (node_planes.hpp): the least-squares plane
// f ~ v + g . (x - c) through the distinct vertices of the node's leaves (the lists the refit
// reads, about one vertex per tet, so the fit reads a quarter of what walking the tets would).
// The fit needs only the moments of the vertices (count, sums of x, x x^T, f and f x), which
// add up from children to parents, so every node's fit comes from one pass over the vertices:
// a walk down each recorded subtree in parallel, then the top nodes.
#include "render/bvh/node_planes.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <unordered_map>

namespace tetray::render {
namespace {

struct Moments {
  double count = 0, f = 0;
  double x[3] = {0, 0, 0}, fx[3] = {0, 0, 0};
  double xx[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};

  void add(const Vertex& v) {
    const double p[3] = {v.x, v.y, v.z};
    count += 1;
    f += v.f;
    for (int i = 0; i < 3; ++i) {
      x[i] += p[i];
      fx[i] += v.f * p[i];
      for (int j = 0; j < 3; ++j) xx[i][j] += p[i] * p[j];
    }
  }

  void add(const Moments& o) {
    count += o.count;
    f += o.f;
    for (int i = 0; i < 3; ++i) {
      x[i] += o.x[i];
      fx[i] += o.fx[i];
      for (int j = 0; j < 3; ++j) xx[i][j] += o.xx[i][j];
    }
  }

  // The plane's gradient solves C g = b for the vertices' covariance C and their covariance
  // b with f (Cramer's rule); a C close to singular (the vertices nearly in one plane) gives no
  // plane, so the traversal never stops at that node.
  NodePlane plane(const Bounds4& box) const {
    NodePlane out;
    if (count < 4) return out;
    double mean[3], c[3][3], b[3];
    const double mean_f = f / count;
    for (int i = 0; i < 3; ++i) mean[i] = x[i] / count;
    for (int i = 0; i < 3; ++i) {
      b[i] = fx[i] / count - mean[i] * mean_f;
      for (int j = 0; j < 3; ++j) c[i][j] = xx[i][j] / count - mean[i] * mean[j];
    }
    const auto det3 = [](const double(&m)[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
             m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double det = det3(c);
    const double scale = (c[0][0] + c[1][1] + c[2][2]) / 3;
    if (!(det > 1e-9 * scale * scale * scale)) return out;
    double g[3];
    for (int k = 0; k < 3; ++k) {
      double m[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = j == k ? b[i] : c[i][j];
      g[k] = det3(m) / det;
    }
    double value = mean_f;
    for (int i = 0; i < 3; ++i) {
      out.gradient[i] = static_cast<float>(g[i]);
      value += g[i] * (0.5 * (double(box.lo[i]) + box.hi[i]) - mean[i]);
    }
    out.value = static_cast<float>(value);
    return out;
  }
};

// Fits the subtree under `node` (children before parents) and returns its moments.
Moments fit_below(const TetVolume& volume, const Bvh& bvh, std::uint32_t node,
                  std::vector<NodePlane>& planes) {
  const BvhNode& n = bvh.nodes[node];
  Moments m;
  if (n.is_leaf()) {
    for (std::uint32_t k = bvh.leaf_vertex_begin[node]; k < bvh.leaf_vertex_begin[node + 1]; ++k)
      m.add(volume.vertices[bvh.leaf_vertices[k]]);
  } else {
    m = fit_below(volume, bvh, n.first, planes);
    m.add(fit_below(volume, bvh, n.first + 1, planes));
  }
  planes[node] = m.plane(n.bounds);
  return m;
}

}  // namespace

void fit_node_planes(const TetVolume& volume, const Bvh& bvh, std::vector<NodePlane>& planes) {
  planes.resize(bvh.nodes.size());
  if (bvh.empty()) return;
  std::vector<Moments> subtree(bvh.subtrees.size());
  tbb::parallel_for(std::size_t{0}, bvh.subtrees.size(), [&](std::size_t s) {
    subtree[s] = fit_below(volume, bvh, bvh.subtrees[s].root, planes);
  });
  std::unordered_map<std::uint32_t, Moments> top;
  for (std::size_t s = 0; s < bvh.subtrees.size(); ++s) top[bvh.subtrees[s].root] = subtree[s];
  for (const std::uint32_t i : bvh.top_nodes_bottom_up) {
    const BvhNode& n = bvh.nodes[i];
    Moments m = top.at(n.first);
    m.add(top.at(n.first + 1));
    planes[i] = m.plane(n.bounds);
    top[i] = m;
  }
}

}  // namespace tetray::render
