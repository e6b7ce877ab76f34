// Shading of primary hits (DESIGN §3): two-sided Lambert with a headlight, the color per
// isovalue or, with color_by, a colormap of a second field interpolated at the hit.
#pragma once

#include "render/camera.hpp"
#include "render/trace.hpp"

namespace tetray::render {

struct ShadeContext {
  const TetVolume& volume;
  const CameraFrame& frame;
  std::span<const IsoSurface> surfaces;
  const int* surface_of_sorted;  // isovalue index (sorted order) -> surfaces index
  const TraceOptions& options;
};

// Writes the pixel of a ray with normalized direction `d` that hit isovalue `iso` (sorted
// index) of volume.tets[tet] at distance t, where the isopolygon has the normal `n` (any length).
void shade_hit(const ShadeContext& ctx, Vec3f d, Vec3f n, float t, int tet, int iso, float rgba[4],
               float& depth);

}  // namespace tetray::render
