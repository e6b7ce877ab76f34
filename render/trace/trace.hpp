// Ray tracing isosurfaces directly on the tets (Wald et al. 2007, §3-5): packets of rays traverse
// the implicit BVH with iso-range culling, first-active speculative descent and interval-arithmetic
// frustum culling; leaves intersect on-the-fly isopolygons.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/fragments.hpp"
#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/iso_set.hpp"
#include "render/scene/trace_options.hpp"
#include "render/trace/level_of_detail.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// "1", "8x8", "16x16", "32x32", "tiled".
const char* to_string(PacketSize packet);

// The counters of Wald et al. 2007, Table 4, per frame.
struct TraceStats {
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;
  std::uint64_t packet_box_tests = 0;  // packet-node visits that needed a geometric test
  std::uint64_t ray_box_tests = 0;     // individual ray-box tests
  std::uint64_t isorange_tests = 0;    // node and tet iso-range tests
  std::uint64_t isopolygon_extractions = 0;
  std::uint64_t ray_isopolygon_tests = 0;        // individual ray-isopolygon tests
  std::uint64_t frustum_culled_isopolygons = 0;  // culled for the whole packet: outside its
                                                 // frustum, or no row covered

  TraceStats& operator+=(const TraceStats& o);
};

// Traces every pixel of `camera` against `volume`/`bvh` for up to kMaxIsovalues isosurfaces
// (nearest hit wins) and shades with a two-sided Lambert headlight. Runs in parallel over
// packets in the calling oneTBB arena. `stats` may be null.
Framebuffer trace(const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats = nullptr);

// The same into `image`, whose storage is reused when it already has the camera's size (every
// pixel is written, so no clearing pass): the form for a time loop.
// With shadowing lights, shadow_terms (when given) receives one image per shadowing light, in the
// order of options.lights: the part of each pixel's color that light contributes, with the
// image's depth and hit keys, so that depth compositing picks the same winner in all of them.
void trace_into(Framebuffer& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                std::span<const IsoSurface> surfaces, const TraceOptions& options,
                TraceStats* stats = nullptr, std::vector<Framebuffer>* shadow_terms = nullptr);

// Transparency by depth peeling (Wald et al. 2007, §8.5; docs/architecture.md §7): a scene
// with a surface of opacity below 1 is traced as layers per pixel. After the first hit, the
// packet's rays that hit a transparent surface are traced again from the same origin, keeping
// only hits strictly after the previous layer's (distance, key) (layer_filter.hpp), until an
// opaque layer or options.max_layers. Each layer is shaded as trace_into shades a hit and
// becomes a zero-length fragment of premultiplied color (alpha: its surface's opacity) at its
// ray distance, the order peeling and the fragment merge share (so the layers this rank keeps
// are its nearest in the merge's order too). A scene of opaque surfaces never runs this code.
inline constexpr int kMaxLayers = 16;

struct LayerImage {
  FragmentImage color;  // per pixel its layers front to back; depths: distances along the ray
  // Per shadowing light of options.lights, in order, with the same fragments' depths, keys and
  // alphas: the part of each layer's color that light gives (premultiplied likewise).
  std::vector<FragmentImage> shadow_terms;
  // Where the packets write the layers, max_layers slots per pixel (the color's, then each
  // shadowing light's), before they are packed into the images above: kept from frame to frame
  // like a trace_into image, since allocating and clearing them each frame cost more than
  // tracing the layers. Only the slots of a pixel's counted layers are ever read.
  std::vector<std::uint8_t> slot_count;
  std::vector<Fragment> slots;
};

// Whether any surface is transparent (opacity below 1).
bool has_transparency(std::span<const IsoSurface> surfaces);

// Traces every pixel's layers into `image` (its storage reused).
void trace_layers(LayerImage& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats = nullptr);

// The view depth (docs/architecture.md §3) of layer `layer` of every pixel of `layers` (+infinity
// where a pixel has fewer), from its ray distance along the pixel's direction in double, into
// `depth` (pixel_count values): the depth shadow rays start from and the EXR carries.
void layer_view_depths(const FragmentImage& layers, const Camera& camera, int layer,
                       std::span<float> depth);

// The same for distances already taken out of the layers: `depth` holds the distances along the
// rays of pixels first, first + 1, ... (+infinity stays), turned into view depths in place, bit
// for bit as layer_view_depths turns them.
void view_depths_of_distances(const Camera& camera, std::size_t first, std::span<float> depth);

}  // namespace tetray::render
