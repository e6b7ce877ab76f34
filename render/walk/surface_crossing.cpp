#include "render/walk/surface_crossing.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::render {

int surface_crossings(std::span<const IsoSurface> surfaces, double g_in, double g_out,
                      SurfaceCrossing* out) {
  int n = 0;
  for (std::size_t k = 0; k < surfaces.size() && n < kMaxIsovalues; ++k) {
    const double c = surfaces[k].value;
    if ((g_in < c) == (g_out < c)) continue;
    const double u = std::clamp((c - g_in) / (g_out - g_in), 0.0, 1.0);
    // Insertion in order of u: a handful of isovalues at most.
    int at = n++;
    for (; at > 0 && out[at - 1].u > u; --at) out[at] = out[at - 1];
    out[at] = {u, static_cast<int>(k)};
  }
  return n;
}

double surface_light(const TetVolume& volume, std::span<const float> field, std::uint32_t tet,
                     Vec3d direction, double ambient) {
  const Tet& t = volume.tets[tet];
  Vec3d x[4];
  double g[4];
  for (int c = 0; c < 4; ++c) {
    const Vertex& v = volume.vertices[static_cast<std::size_t>(t.v[c])];
    x[c] = {v.x, v.y, v.z};
    g[c] = field.empty() ? v.f : field[static_cast<std::size_t>(t.v[c])];
  }
  // The gradient of the linear field: sum over the edges from x0 of (g_k - g_0) times the dual
  // basis vector, the cross product of the other two edges over the volume's determinant.
  const Vec3d e1 = x[1] - x[0], e2 = x[2] - x[0], e3 = x[3] - x[0];
  const Vec3d gradient =
      (g[1] - g[0]) * cross(e2, e3) + (g[2] - g[0]) * cross(e3, e1) + (g[3] - g[0]) * cross(e1, e2);
  const double length = std::sqrt(dot(gradient, gradient));
  const double cos = length > 0 ? std::abs(dot(gradient, direction)) / length : 1.0;
  return ambient + (1 - ambient) * std::min(1.0, cos);
}

Gathered surface_layer(const IsoSurface& surface, double light) {
  Gathered g;
  const double a = surface.opacity;
  g.color = {a * light * surface.color.r, a * light * surface.color.g, a * light * surface.color.b};
  g.transmittance = 1 - a;
  return g;
}

}  // namespace tetray::render
