#include "render/scene/shade.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/scene/colormap.hpp"

namespace tetray::render {
namespace {

// Barycentric coordinates of x (local coordinates) in the tet; a degenerate tet gives each
// vertex a quarter.
std::array<double, 4> barycentric(const TetVolume& volume, const Tet& tet, Vec3f x) {
  Vec3d p[4];
  for (int k = 0; k < 4; ++k) {
    const Vertex& v = volume.vertices[tet.v[k]];
    p[k] = {v.x, v.y, v.z};
  }
  const Vec3d a = p[1] - p[0], b = p[2] - p[0], e = p[3] - p[0], r = static_cast<Vec3d>(x) - p[0];
  const double det = dot(a, cross(b, e));
  if (std::abs(det) <= 1e-30) return {0.25, 0.25, 0.25, 0.25};
  const double l1 = dot(r, cross(b, e)) / det, l2 = dot(a, cross(r, e)) / det,
               l3 = dot(a, cross(b, r)) / det;
  return {1 - l1 - l2 - l3, l1, l2, l3};
}

// Value of the color field at x by barycentric interpolation.
float interpolate_color_field(const TetVolume& volume, const Tet& tet, Vec3f x) {
  const std::array<double, 4> l = barycentric(volume, tet, x);
  double value = 0;
  for (int k = 0; k < 4; ++k) value += l[k] * volume.color_field[tet.v[k]];
  return static_cast<float>(value);
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

namespace tetray::render {

LocalLights local_lights(const Lights& lights, Vec3d origin) {
  LocalLights local;
  local.count = std::min(lights.count, kMaxLights);
  for (int k = 0; k < local.count; ++k) {
    const Light& l = lights.light[k];
    local.kind[k] = l.kind;
    local.shadows[k] = l.shadows && l.kind != LightKind::headlight;
    local.vector[k] = l.kind == LightKind::point ? static_cast<Vec3f>(l.vector - origin)
                                                 : static_cast<Vec3f>(-normalize(l.vector));
  }
  return local;
}

void light_terms(const ShadeContext& ctx, const LocalLights& lights, const RayHits& hits, Vec3f eye,
                 float* light, float* const* shadow_factor) {
  const float ambient = ctx.options.ambient;
  const float share = (1 - ambient) / static_cast<float>(std::max(lights.count, 1));
  for (int r = 0; r < hits.count; ++r) {
    const Vec3f d{hits.dx[r], hits.dy[r], hits.dz[r]};
    Vec3f n{hits.nx[r], hits.ny[r], hits.nz[r]};
    const float len = length(n);
    n = len > 0 ? (1 / len) * n : -1.0f * d;  // no normal: lit as if facing the eye
    if (dot(n, d) > 0) n = -1.0f * n;         // turned towards the viewer
    const Vec3f p = eye + hits.t[r] * d;
    float diffuse = 0;
    int shadowing = 0;
    for (int k = 0; k < lights.count; ++k) {
      float term = 0;
      if (lights.kind[k] == LightKind::headlight) {
        term = -dot(n, d);
      } else {
        const Vec3f to_light =
            lights.kind[k] == LightKind::point ? lights.vector[k] - p : lights.vector[k];
        const float distance = length(to_light);
        term = distance > 0 ? std::max(0.0f, dot(n, to_light) / distance) : 0.0f;
      }
      diffuse += term;
      if (lights.shadows[k]) shadow_factor[shadowing++][r] = share * term;
    }
    light[r] = ambient + share * diffuse;
  }
}

void interpolate_normals(const ShadeContext& ctx, const RayHits& hits, const std::int32_t* tet,
                         float* nx, float* ny, float* nz) {
  const Vec3f eye = static_cast<Vec3f>(ctx.frame.eye - ctx.volume.origin);
  for (int r = 0; r < hits.count; ++r) {
    if (tet[r] < 0) continue;
    const Tet& t = ctx.volume.tets[tet[r]];
    const Vec3f x = eye + hits.t[r] * Vec3f{hits.dx[r], hits.dy[r], hits.dz[r]};
    const std::array<double, 4> l = barycentric(ctx.volume, t, x);
    Vec3d n{};
    for (int k = 0; k < 4; ++k) n = n + l[k] * static_cast<Vec3d>(ctx.volume.gradients[t.v[k]]);
    // Where the vertex gradients cancel (a saddle between opposite slopes), the isopolygon's
    // own normal stays.
    if (dot(n, n) == 0) continue;
    nx[r] = static_cast<float>(n.x);
    ny[r] = static_cast<float>(n.y);
    nz[r] = static_cast<float>(n.z);
  }
}

}  // namespace tetray::render
