#include "render/trace/shade.hpp"

#include <cmath>

#include "render/trace/colormap.hpp"

namespace tetray::render {
namespace {

// Value of the color field at x (local coordinates) by barycentric interpolation; degenerate
// tets take the mean of their vertices.
float interpolate_color_field(const TetVolume& volume, const Tet& tet, Vec3f x) {
  Vec3d p[4];
  double c[4];
  for (int k = 0; k < 4; ++k) {
    const Vertex& v = volume.vertices[tet.v[k]];
    p[k] = {v.x, v.y, v.z};
    c[k] = volume.color_field[tet.v[k]];
  }
  const Vec3d a = p[1] - p[0], b = p[2] - p[0], e = p[3] - p[0], r = static_cast<Vec3d>(x) - p[0];
  const double det = dot(a, cross(b, e));
  if (std::abs(det) <= 1e-30) return static_cast<float>(0.25 * (c[0] + c[1] + c[2] + c[3]));
  const double l1 = dot(r, cross(b, e)) / det, l2 = dot(a, cross(r, e)) / det,
               l3 = dot(a, cross(b, r)) / det;
  return static_cast<float>((1 - l1 - l2 - l3) * c[0] + l1 * c[1] + l2 * c[2] + l3 * c[3]);
}

}  // namespace

// Written for the compiler to vectorize: no aliasing of the outputs, the division done in every
// lane and its result selected.
void light_and_depth(const ShadeContext& ctx, const RayHits& hits, float* light, float* depth) {
  const float ambient = ctx.options.ambient;
  const Vec3d forward = ctx.frame.forward;
  float* __restrict light_out = light;
  float* __restrict depth_out = depth;
  for (int r = 0; r < hits.count; ++r) {
    const float nx = hits.nx[r], ny = hits.ny[r], nz = hits.nz[r];
    const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
    const float ratio = std::abs(nx * hits.dx[r] + ny * hits.dy[r] + nz * hits.dz[r]) / len;
    light_out[r] = ambient + (1 - ambient) * (len > 0 ? ratio : 1.0f);
  }
  for (int r = 0; r < hits.count; ++r) {
    const double along = double(hits.dx[r]) * forward.x + double(hits.dy[r]) * forward.y +
                         double(hits.dz[r]) * forward.z;
    depth_out[r] = static_cast<float>(hits.t[r] * along);
  }
}

void field_color(const ShadeContext& ctx, int tet, Vec3f d, float t, float rgb[3]) {
  const ColorBy& by = ctx.options.color_by;
  const Vec3f eye = static_cast<Vec3f>(ctx.frame.eye - ctx.volume.origin);
  const float value = interpolate_color_field(ctx.volume, ctx.volume.tets[tet], eye + t * d);
  const float span = by.range_hi - by.range_lo;
  by.colormap->lookup(span > 0 ? (value - by.range_lo) / span : 0.5f, rgb);
}

}  // namespace tetray::render
