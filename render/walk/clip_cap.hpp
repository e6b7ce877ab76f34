// Caps of a clip region (Wald et al. 2007, §7): where a clip plane or a box face cuts the mesh,
// the cut surface shows a point field through a colormap. Per pixel, the point where the ray
// enters the kept region through a plane or face is located in this rank's tets through the BVH
// (point_locate.hpp), or by walking from the previous pixel's tet; inside one, it is a hit at that
// depth whose color is the field interpolated barycentrically there, lit with the plane's normal.
// It competes with the isosurface hit of the pixel by the tie rule (docs/architecture.md §3) with
// the containing tet's key, so a cap composites across ranks like any hit and the image does not
// depend on the rank count. Runs only for scenes with a cap: a scene without one never calls it.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/clip_region.hpp"
#include "render/scene/colormap.hpp"
#include "render/scene/trace_options.hpp"
#include "render/volume/tet_volume.hpp"
#include "render/walk/face_adjacency.hpp"

namespace tetray::render {

struct ClipCap {
  const Colormap* colormap = nullptr;
  float range_lo = 0, range_hi = 1;
  std::span<const float> field;  // per vertex of the volume, in the vertex store's order
};

// Where a ray from `eye` along the unit direction `d` (both local) enters the region: its
// distance and the outward normal of the plane or box face it enters through. Empty when the
// eye is inside the region (nothing is cut in front of it) or the ray misses it.
struct RegionEntry {
  double t = 0;
  Vec3d normal;
};
std::optional<RegionEntry> enter_region(const ClipRegion& region, Vec3d origin, Vec3d eye, Vec3d d);

// Draws the cap of options.clip over `image`, which trace_into drew with the same camera and
// options; with shadow_terms (trace_into's), writes the cap's share of each light there too.
// With the volume's face adjacency, a point not in the previous pixel's tet is looked for by
// walking from that tet (locate_by_walking) before descending the BVH; the image is the same.
void draw_clip_cap(Framebuffer& image, const TetVolume& volume, const Bvh& bvh,
                   const Camera& camera, const TraceOptions& options, const ClipCap& cap,
                   std::vector<Framebuffer>* shadow_terms = nullptr,
                   const FaceAdjacency<Tet20>* adjacency = nullptr);

}  // namespace tetray::render
