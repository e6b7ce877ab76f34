// What a frame asks of the tracer (render/trace/trace.hpp), read also by the walk's clip caps
// and surfaces (render/walk/): the grouping of rays, coloring by a field, the headlight's
// ambient term, smooth normals, clipping, lights, level of detail and transparency.
#pragma once

#include <array>
#include <span>

#include "render/bvh/node_planes.hpp"
#include "render/scene/clip_region.hpp"
#include "render/scene/colormap.hpp"
#include "render/scene/iso_surface.hpp"
#include "render/scene/lights.hpp"

namespace tetray::render {

// Rays traced together (Wald et al. 2007, §3): single rays, or square packets, each traversing
// the BVH; or (tiled, the default) 128 x 128 tiles that traverse it once as a frustum and set up
// their isopolygons a lane batch at a time for their 32 x 32 packets
// (render/trace/tile_polygons.hpp). Every choice gives bitwise the same image; larger packets share
// more of the traversal and of each isopolygon's set-up, tiles the most.
enum class PacketSize { single, p8x8, p16x16, p32x32, tiled };
inline constexpr std::array kPacketSizes = {PacketSize::single, PacketSize::p8x8,
                                            PacketSize::p16x16, PacketSize::p32x32,
                                            PacketSize::tiled};

// Coloring by a second per-vertex field (TetVolume::color_field) through a colormap instead
// of the per-isovalue colors. Without it no field is gathered at the hits.
struct ColorBy {
  const Colormap* colormap = nullptr;  // null: use IsoSurface::color
  float range_lo = 0, range_hi = 1;
};

// Level of detail (render/trace/level_of_detail.hpp): what a scene asks for. Empty planes or a
// zero pixel error mean exact images.
struct LevelOfDetail {
  float node_pixels = 0;                // node width allowed, in pixel footprints
  std::span<const NodePlane> planes{};  // one per BVH node (fit_node_planes)

  bool enabled() const { return node_pixels > 0 && !planes.empty(); }
};

struct TraceOptions {
  PacketSize packet = PacketSize::tiled;
  bool collect_stats = false;  // off: the hot path pays nothing for counting
  ColorBy color_by{};
  float ambient = 0.15f;  // Lambert headlight: color * (ambient + (1 - ambient) |cos|)
  // Normals from the interpolated vertex gradients (TetVolume::gradients; flat where they are
  // missing) instead of each isopolygon's plane.
  bool smooth = false;
  // Only the part of space this region keeps is drawn (Wald et al. 2007, §7); empty: all of it,
  // at no cost.
  ClipRegion clip{};
  // Beyond a lone headlight, each light's term is computed per hit; a shadowing light's term is
  // also written apart (trace_into's shadow_terms) for apply_shadows once visibility is known.
  Lights lights{};
  // Where a BVH node is narrower than lod.node_pixels pixels, its proxy surface is drawn instead
  // of its tets (render/trace/level_of_detail.hpp); off by default: exact images, and nothing of it
  // runs.
  LevelOfDetail lod{};
  // Transparent surfaces: the layers per pixel trace_layers peels at most (1..kMaxLayers).
  int max_layers = 4;
};

}  // namespace tetray::render
