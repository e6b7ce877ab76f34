// Isosurfaces met along the walk (docs/architecture.md §8, "surfaces as hits along the walk"):
// inside a tet a point field is linear, so along one tet's stretch it goes linearly from its
// value at the entry face to its value at the exit face, and a crossing of an isovalue is found
// in closed form. A crossing counts where the field passes from below the isovalue to at or
// above it, or back: the field at a face is the same bit for bit from both tets sharing it
// (face_crossing.hpp), so a surface the ray passes through at a face is met once, in one of the
// two tets; where the field only touches the isovalue at a face (a ridge or valley lying in
// faces), it is met twice at the same depth or not at all, the same on every rank count. The
// surface is a layer lit by the headlight, flat per tet (the field's gradient in the tet is the
// isopolygon's normal), its color times its opacity over what lies behind; the volume in front
// of and behind it is integrated on its own (volume_render.cpp).
#pragma once

#include <cstdint>
#include <span>

#include "render/scene/iso_set.hpp"
#include "render/scene/iso_surface.hpp"
#include "render/volume/tet_volume.hpp"
#include "render/walk/segment_integral.hpp"

namespace tetray::render {

// Trivial, so that a ray's array of them costs nothing to set up per tet.
struct SurfaceCrossing {
  double u;     // where along the stretch, in [0, 1]
  int surface;  // index into the surfaces
};

// The crossings of the surfaces' isovalues on a stretch along which the field goes linearly from
// g_in to g_out, in order along the ray (ties in the surfaces' order), into `out`, which has
// room for kMaxIsovalues; returns how many.
int surface_crossings(std::span<const IsoSurface> surfaces, double g_in, double g_out,
                      SurfaceCrossing* out);

// The headlight's factor ambient + (1 - ambient) |cos| at a crossing in volume.tets[tet] of a ray
// along the unit `direction`, the normal the gradient of `field` (per vertex; empty: the
// volume's own) in the tet.
double surface_light(const TetVolume& volume, std::span<const float> field, std::uint32_t tet,
                     Vec3d direction, double ambient);

// A surface's layer lit by `light`: premultiplied color and what it lets through.
Gathered surface_layer(const IsoSurface& surface, double light);

}  // namespace tetray::render
