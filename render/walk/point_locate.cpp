#include "render/walk/point_locate.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/bvh/bounds.hpp"
#include "render/walk/face_crossing.hpp"

namespace tetray::render {
namespace {

// Relative slack of the inside test: a point on a shared face belongs to both tets.
constexpr double kFaceSlack = 1e-10;
constexpr int kLocateStack = 130;  // pending nodes: one per level, plus the pair just pushed

bool box_contains(const Bounds4& b, Vec3d p) {
  for (int a = 0; a < 3; ++a) {
    const double pad = kFaceSlack * (1.0 + std::abs(b.lo[a]) + std::abs(b.hi[a]));
    if (p[a] < b.lo[a] - pad || p[a] > b.hi[a] + pad) return false;
  }
  return true;
}

// The point's barycentric weights in tet t, inside or not; false for a degenerate tet.
bool weights_in(const TetVolume& volume, std::uint32_t t, Vec3d p, std::array<double, 4>& w) {
  const Tet& tet = volume.tets[t];
  Vec3d x[4];
  for (int c = 0; c < 4; ++c) x[c] = vertex_position(volume, static_cast<std::uint32_t>(tet.v[c]));
  const Vec3d e1 = x[1] - x[0], e2 = x[2] - x[0], e3 = x[3] - x[0], q = p - x[0];
  const double det = dot(e1, cross(e2, e3));
  if (det == 0) return false;
  w[1] = dot(q, cross(e2, e3)) / det;
  w[2] = dot(e1, cross(q, e3)) / det;
  w[3] = dot(e1, cross(e2, q)) / det;
  w[0] = 1.0 - w[1] - w[2] - w[3];
  return true;
}

// The corner of tet t that the point equals in float, or -1.
int vertex_at(const TetVolume& volume, std::uint32_t t, Vec3d p) {
  const Vec3f pf = static_cast<Vec3f>(p);
  for (int c = 0; c < 4; ++c) {
    const Vertex& v = volume.vertices[volume.tets[t].v[c]];
    if (pf.x == v.x && pf.y == v.y && pf.z == v.z) return c;
  }
  return -1;
}

std::optional<PointLocation> in_tet(const TetVolume& volume, std::uint32_t t, Vec3d p) {
  PointLocation at{t, {}};
  if (const int c = vertex_at(volume, t, p); c >= 0) {
    at.weight[static_cast<std::size_t>(c)] = 1;
    return at;
  }
  if (!weights_in(volume, t, p, at.weight)) return std::nullopt;
  for (double w : at.weight) {
    if (w < -kFaceSlack) return std::nullopt;
  }
  return at;
}

bool strictly_inside(const PointLocation& at) {
  return std::all_of(at.weight.begin(), at.weight.end(), [](double w) { return w > kFaceSlack; });
}

}  // namespace

bool within_bounds(const Bvh& bvh, Vec3d local) {
  return !bvh.empty() && box_contains(bvh.nodes[0].bounds, local);
}

std::optional<PointLocation> locate_strictly_inside(const TetVolume& volume, std::uint32_t tet,
                                                    Vec3d local) {
  std::optional<PointLocation> at = in_tet(volume, tet, local);
  if (!at || !strictly_inside(*at)) return std::nullopt;
  return at;
}

std::optional<PointLocation> locate_by_walking(const TetVolume& volume,
                                               const FaceAdjacency<Tet20>& adjacency,
                                               std::uint32_t from, Vec3d local) {
  PointLocation at{from, {}};
  for (int step = 0; step <= kLocateWalkSteps; ++step) {
    // A point on a vertex to float precision is in_tet's special case: ask locate_point.
    if (vertex_at(volume, at.tet, local) >= 0) return std::nullopt;
    if (!weights_in(volume, at.tet, local, at.weight)) return std::nullopt;
    if (strictly_inside(at)) return at;  // in_tet's weights: the same computation
    if (step == kLocateWalkSteps) break;
    // Across the face opposite the vertex of the most negative weight.
    const auto c =
        static_cast<int>(std::min_element(at.weight.begin(), at.weight.end()) - at.weight.begin());
    if (!(at.weight[static_cast<std::size_t>(c)] < 0)) return std::nullopt;  // on a face
    const Tet& tet = volume.tets[at.tet];
    const auto v = [&](int k) { return static_cast<std::uint32_t>(tet.v[(c + k) % 4]); };
    const std::uint32_t next =
        adjacency.tets[at.tet].neighbor[vertex_order(v(0), v(1), v(2), v(3))];
    if (next == kBoundaryFace) return std::nullopt;
    at.tet = next;
  }
  return std::nullopt;
}

std::optional<PointLocation> locate_point(const TetVolume& volume, const Bvh& bvh, Vec3d local) {
  if (bvh.empty()) return std::nullopt;
  std::optional<PointLocation> best;
  // On the stack, not the heap: a cap locates a point for most of its pixels. The builders
  // bound the depth well below the traversal's 128 (packet_traversal.hpp), and a walk down
  // holds at most one pending node per level.
  std::uint32_t stack[kLocateStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = bvh.nodes[stack[--top]];
    if (!box_contains(node.bounds, local)) continue;
    if (!node.is_leaf()) {
      stack[top++] = node.first;
      stack[top++] = node.first + 1;
      continue;
    }
    for (std::uint32_t t = node.first; t < node.first + node.count; ++t) {
      // The tet's own box first (the padding covers every point in_tet accepts): most tets of
      // a leaf are ruled out without the weights in double.
      if (!box_contains(tet_bounds(volume, volume.tets[t]), local)) continue;
      const std::optional<PointLocation> found = in_tet(volume, t, local);
      if (found && (!best || volume.tet_ids[t] < volume.tet_ids[best->tet])) best = found;
    }
  }
  return best;
}

}  // namespace tetray::render
