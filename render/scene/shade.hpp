// Shading of primary hits (docs/architecture.md §3): two-sided Lambert with a headlight, the color
// per isovalue or, with color_by, a colormap of a second field interpolated at the hit.
#pragma once

#include <span>
#include "render/scene/camera.hpp"
#include "render/scene/lights.hpp"

#include "render/scene/trace_options.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

struct ShadeContext {
  const TetVolume& volume;
  const CameraFrame& frame;
  std::span<const IsoSurface> surfaces;
  const int* surface_of_sorted;  // isovalue index (sorted order) -> surfaces index
  const TraceOptions& options;
};

// The hits of a packet's rays, structure of arrays: normalized direction d, isopolygon normal n
// (any length), distance t.
struct RayHits {
  const float *dx, *dy, *dz;
  const float *nx, *ny, *nz;
  const float* t;
  int count;
};

// Headlight factor and view depth of every ray of `hits` at once: the per-pixel square roots,
// divisions and double-precision depths are the costly part of shading, and run vectorized.
// Values of rays that hit nothing are meaningless.
void light_and_depth(const ShadeContext& ctx, const RayHits& hits, float* light, float* depth);

// Smooth shading: replaces the normal of each ray that hit (tet[r] >= 0) by the field gradient
// interpolated barycentrically at its hit point from the tet's vertex gradients
// (TetVolume::gradients, which must be filled).
void interpolate_normals(const ShadeContext& ctx, const RayHits& hits, const std::int32_t* tet,
                         float* nx, float* ny, float* nz);

// A scene's lights in the volume's local float coordinates: point lights by position,
// directional ones by the unit vector towards the light.
struct LocalLights {
  int count = 0;
  LightKind kind[kMaxLights];
  Vec3f vector[kMaxLights];
  bool shadows[kMaxLights];
};
LocalLights local_lights(const Lights& lights, Vec3d origin);

// With several lights, or other than a headlight: overwrites `light` with the factor of every
// ray of `hits` (the eye at `eye`, local) and writes, per shadowing light j in order, the part
// of that factor the light gives to shadow_factor[j].
void light_terms(const ShadeContext& ctx, const LocalLights& lights, const RayHits& hits, Vec3f eye,
                 float* light, float* const* shadow_factor);

// The color field's colormap value at the hit point eye + t d of a ray in volume.tets[tet].
void field_color(const ShadeContext& ctx, int tet, Vec3f d, float t, float rgb[3]);

// Whether hits take their color from the color field's colormap (color_by, its field loaded)
// rather than from their surfaces.
inline bool colors_by_field(const ShadeContext& ctx) {
  return ctx.options.color_by.colormap && !ctx.volume.color_field.empty();
}

// The color of a ray with normalized direction `d` that hit isovalue `iso` (sorted index) of
// volume.tets[tet] at distance t, lit by `light`: the surface's color, or with color_by the
// field's; only the latter needs the hit point and reads the tet (a random access into the
// tets per pixel that a plain surface does not need).
inline void shade_color(const ShadeContext& ctx, Vec3f d, float t, int tet, int iso, float light,
                        float rgba[4]) {
  float rgb[3];
  if (colors_by_field(ctx)) {
    field_color(ctx, tet, d, t, rgb);
  } else {
    const Rgb& c = ctx.surfaces[ctx.surface_of_sorted[iso]].color;
    rgb[0] = c.r;
    rgb[1] = c.g;
    rgb[2] = c.b;
  }
  for (int k = 0; k < 3; ++k) rgba[k] = rgb[k] * light;
  rgba[3] = 1.0f;
}

}  // namespace tetray::render
