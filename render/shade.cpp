#include "render/shade.hpp"

#include <cmath>

#include "render/colormap.hpp"

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

// The surface's color, or the color field's value at the hit point eye + t d; only the latter
// needs the point and reads the tet (a random access into the tets per pixel that a plain
// surface does not need).
void base_color(const ShadeContext& ctx, int tet_index, Vec3f d, float t, int surface,
                float rgb[3]) {
  const ColorBy& by = ctx.options.color_by;
  if (by.colormap && !ctx.volume.color_field.empty()) {
    const Vec3f eye = static_cast<Vec3f>(ctx.frame.eye - ctx.volume.origin);
    const float value =
        interpolate_color_field(ctx.volume, ctx.volume.tets[tet_index], eye + t * d);
    const float span = by.range_hi - by.range_lo;
    by.colormap->lookup(span > 0 ? (value - by.range_lo) / span : 0.5f, rgb);
    return;
  }
  const Rgb& c = ctx.surfaces[surface].color;
  rgb[0] = c.r;
  rgb[1] = c.g;
  rgb[2] = c.b;
}

}  // namespace

void shade_hit(const ShadeContext& ctx, Vec3f d, Vec3f n, float t, int tet_index, int iso,
               float rgba[4], float& depth) {
  const int surface = ctx.surface_of_sorted[iso];
  const float len = length(n);
  const float cosine = len > 0 ? std::abs(dot(n, d)) / len : 1.0f;
  const float ambient = ctx.options.ambient;
  const float light = ambient + (1 - ambient) * cosine;
  float rgb[3];
  base_color(ctx, tet_index, d, t, surface, rgb);
  for (int k = 0; k < 3; ++k) rgba[k] = rgb[k] * light;
  rgba[3] = 1.0f;
  depth = static_cast<float>(t * dot(static_cast<Vec3d>(d), ctx.frame.forward));
}

}  // namespace tetray::render
