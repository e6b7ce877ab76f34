// The proxy isosurface of a node (level_of_detail.hpp): the plane f(x) = value + g . (x - c)
// cut at the isovalue, clipped to the node's box by the box's twelve edges, its corners put in
// order around their mean and split into a fan of at most two isopolygons.
#include "render/trace/level_of_detail.hpp"

#include <array>
#include <cmath>

namespace tetray::render {
namespace {

Vec3d corner_of(const Bounds4& box, int k) {
  return {(k & 1) ? box.hi[0] : box.lo[0], (k & 2) ? box.hi[1] : box.lo[1],
          (k & 4) ? box.hi[2] : box.lo[2]};
}

// Two unit vectors spanning the plane normal to g.
void plane_basis(const Vec3d& g, Vec3d& u, Vec3d& v) {
  const Vec3d a{std::abs(g.x), std::abs(g.y), std::abs(g.z)};
  const Vec3d axis = a.x <= a.y && a.x <= a.z ? Vec3d{1, 0, 0}
                     : a.y <= a.z             ? Vec3d{0, 1, 0}
                                              : Vec3d{0, 0, 1};
  u = normalize(cross(g, axis));
  v = normalize(cross(g, u));
}

Isopolygon polygon_of(const std::array<Vec3d, 6>& points, std::array<int, 4> corners,
                      int vertex_count) {
  Isopolygon poly;
  poly.vertex_count = vertex_count;
  alignas(16) float xyz[3][4];
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) xyz[c][k] = static_cast<float>(points[corners[k]][c]);
  for (int c = 0; c < 3; ++c) poly.xyz[c] = simd::Float4::load_aligned(xyz[c]);
  return poly;
}

}  // namespace

int proxy_isopolygons(const Bounds4& box, const NodePlane& plane, float iso, Isopolygon (&out)[2]) {
  const Vec3d g{plane.gradient[0], plane.gradient[1], plane.gradient[2]};
  const Vec3d centre = 0.5 * (corner_of(box, 0) + corner_of(box, 7));
  double value[8];
  for (int k = 0; k < 8; ++k) value[k] = plane.value + dot(g, corner_of(box, k) - centre) - iso;
  std::array<Vec3d, 6> points;
  int count = 0;
  for (int k = 0; k < 8; ++k)
    for (int axis = 1; axis < 8; axis <<= 1) {
      const int j = k | axis;
      if (j == k || (value[k] >= 0) == (value[j] >= 0) || count == 6) continue;
      const double s = value[k] / (value[k] - value[j]);
      points[count++] = corner_of(box, k) + s * (corner_of(box, j) - corner_of(box, k));
    }
  if (count < 3) return 0;
  Vec3d mean{};
  for (int k = 0; k < count; ++k) mean = mean + (1.0 / count) * points[k];
  Vec3d u, v;
  plane_basis(g, u, v);
  double angle[6];
  for (int k = 0; k < count; ++k)
    angle[k] = std::atan2(dot(points[k] - mean, v), dot(points[k] - mean, u));
  // Each corner's place around the mean is the number of corners before it by angle (ties by
  // index): at most six corners, so no sort.
  std::array<Vec3d, 6> ring;
  for (int k = 0; k < count; ++k) {
    int place = 0;
    for (int j = 0; j < count; ++j) place += angle[j] < angle[k] || (angle[j] == angle[k] && j < k);
    ring[place] = points[k];
  }
  // A fan from corner 0: (0 1 2 3) and (0 3 4 5); a triangle repeats its first corner.
  const auto piece = [&](int a, int b, int c, int d) {
    return d < count ? polygon_of(ring, {a, b, c, d}, 4) : polygon_of(ring, {a, b, c, a}, 3);
  };
  out[0] = piece(0, 1, 2, 3);
  if (count <= 4) return 1;
  out[1] = piece(0, 3, 4, 5);
  return 2;
}

}  // namespace tetray::render
