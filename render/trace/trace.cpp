// Frame driver: splits the image into 32 x 32 blocks traced in parallel, each as packets of
// the chosen size; the leaf operation intersects on-the-fly isopolygons (Wald et al. 2007, §4.4: no
// cache) of every tet whose own range straddles an isovalue (§5.2 V).
#include "render/trace/trace.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>

#include "render/scene/shade.hpp"
#include "render/trace/frame_pixels.hpp"
#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/layer_filter.hpp"
#include "render/trace/layer_peeling.hpp"
#include "render/trace/leaf_intersect.hpp"
#include "render/trace/packet_traversal.hpp"
#include "render/trace/proxy_intersect.hpp"
#include "render/trace/tile_trace.hpp"

namespace tetray::render {
namespace {

constexpr int kBlock = 32;  // pixels a side of a parallel task, a multiple of every packet size

VolumeExtent volume_extent(const Bvh& bvh, Vec3f eye) {
  VolumeExtent extent;
  extent.magnitude = std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)});
  if (bvh.empty()) return extent;
  const Bounds4& root = bvh.nodes[0].bounds;
  for (int a = 0; a < 3; ++a) {
    extent.lo[a] = root.lo[a] - eye[a];
    extent.hi[a] = root.hi[a] - eye[a];
    extent.magnitude = std::max({extent.magnitude, std::abs(root.lo[a]), std::abs(root.hi[a])});
  }
  return extent;
}

// Narrows the extent to the clip box (with its margin): a packet whose frustum misses the kept
// part of the volume sees only background.
void clip_extent(VolumeExtent& extent, const LocalClip& clip, Vec3f eye) {
  if (!clip.has_box) return;
  for (int a = 0; a < 3; ++a) {
    extent.lo[a] = std::max(extent.lo[a], clip.lo[a] - clip.margin - eye[a]);
    extent.hi[a] = std::min(extent.hi[a], clip.hi[a] + clip.margin - eye[a]);
  }
}

// Traces the packet's rays through the one traversal, with the node and hit filters of the
// scene's clip region (none without one) or of a layer (layer_filter.hpp), and the scene's
// level of detail (exact without one): a node the traversal stopped at, or a leaf narrow
// enough, gives its proxy surface instead of its tets.
template <int S, bool kStats, bool kLod, typename NodeFilter, typename HitFilter>
void trace_rays(const Frame& f, RayPacket<S>& packet, TraceStats& stats, NodeFilter node_filter,
                HitFilter hit_filter) {
  const auto lod = lod_policy<kLod>(f);
  PacketTraversal<RayPacket<S>, kStats, NodeFilter, decltype(lod)> traversal(
      f.bvh, f.isos, packet, stats, node_filter, lod);
  IsopolygonIntersector<S, kStats, HitFilter> intersector(packet, stats, hit_filter);
  traversal.run([&](const BvhNode& node, int first_active) {
    if (gives_proxy(f, lod, node, packet.eye)
            ? intersect_proxy(f.volume, f.bvh, f.lod, f.isos, node, first_active, intersector)
            : intersect_leaf<S, kStats>(f.volume, f.isos, node, first_active, intersector, packet,
                                        stats))
      update_tmax_bound(packet);
  });
}

template <int S, bool kStats, bool kClip, bool kLod>
void trace_packet(const Frame& f, int x0, int y0, Framebuffer& image, TraceStats& stats) {
  PacketFrustum frustum{};  // single rays use none
  if constexpr (S > 1) {
    frustum = tile_frustum<S>(f.camera, f.view, f.extent.magnitude, x0, y0);
    if (f.bvh.empty() || f.extent.empty() || frustum.misses_box(f.extent.lo, f.extent.hi)) {
      if (f.layers) return;  // no layers: the slots' counts are zero
      return write_background<S, kStats>(f, x0, y0, image, stats);
    }
  }
  RayPacket<S> packet;
  setup_packet(packet, f.camera, f.view, f.directions, f.volume.origin, frustum, f.extent.magnitude,
               x0, y0);
  trace_rays<S, kStats, kLod>(f, packet, stats, ClipNodes<kClip>(f.clip), ClipHits<kClip>(f.clip));
  if (f.layers)
    return peel_layers<S, kStats, kClip>(f, packet, x0, y0, stats, [&](auto nodes, auto hits) {
      trace_rays<S, kStats, kLod>(f, packet, stats, nodes, hits);
    });
  write_pixels<S, kStats>(f, packet, x0, y0, image, stats);
}

template <int S, bool kStats, bool kClip, bool kLod>
void trace_blocks(const Frame& f, Framebuffer& image, TraceStats* total) {
  const int blocks_x = (f.camera.width + kBlock - 1) / kBlock;
  const int blocks = blocks_x * ((f.camera.height + kBlock - 1) / kBlock);
  tbb::enumerable_thread_specific<TraceStats> stats;
  tbb::parallel_for(0, blocks, [&](int b) {
    TraceStats& local = stats.local();
    const int bx = b % blocks_x * kBlock, by = b / blocks_x * kBlock;
    for (int y = by; y < by + kBlock && y < f.camera.height; y += S)
      for (int x = bx; x < bx + kBlock && x < f.camera.width; x += S)
        trace_packet<S, kStats, kClip, kLod>(f, x, y, image, local);
  });
  if (total) {
    for (const TraceStats& s : stats) *total += s;
  }
}

template <int S, bool kClip, bool kLod>
void trace_with(const Frame& f, Framebuffer& image, bool collect, TraceStats* stats) {
  if (collect) {
    trace_blocks<S, true, kClip, kLod>(f, image, stats);
  } else {
    trace_blocks<S, false, kClip, kLod>(f, image, nullptr);
  }
}

template <int S, bool kClip>
void trace_with(const Frame& f, Framebuffer& image, bool collect, TraceStats* stats) {
  if (f.lod.enabled()) {
    trace_with<S, kClip, true>(f, image, collect, stats);
  } else {
    trace_with<S, kClip, false>(f, image, collect, stats);
  }
}

template <int S>
void trace_with(const Frame& f, Framebuffer& image, bool clipped, bool collect, TraceStats* stats) {
  if (clipped) {
    trace_with<S, true>(f, image, collect, stats);
  } else {
    trace_with<S, false>(f, image, collect, stats);
  }
}

}  // namespace

const char* to_string(PacketSize packet) {
  switch (packet) {
    case PacketSize::single:
      return "1";
    case PacketSize::p8x8:
      return "8x8";
    case PacketSize::p16x16:
      return "16x16";
    case PacketSize::p32x32:
      return "32x32";
    case PacketSize::tiled:
      return "tiled";
  }
  return "?";
}

TraceStats& TraceStats::operator+=(const TraceStats& o) {
  rays += o.rays;
  hits += o.hits;
  packet_box_tests += o.packet_box_tests;
  ray_box_tests += o.ray_box_tests;
  isorange_tests += o.isorange_tests;
  isopolygon_extractions += o.isopolygon_extractions;
  ray_isopolygon_tests += o.ray_isopolygon_tests;
  frustum_culled_isopolygons += o.frustum_culled_isopolygons;
  return *this;
}

Framebuffer trace(const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats) {
  Framebuffer image;
  trace_into(image, volume, bvh, camera, surfaces, options, stats, nullptr);
  return image;
}

namespace {

// The frame's table of surface colors, unless a colormap colors the hits (Frame::iso_rgba).
void set_surface_colors(Frame& f) {
  f.surface_colors = !colors_by_field(f.shade);
  for (int k = 0; k < f.isos.count; ++k) {
    const Rgb& c = f.shade.surfaces[f.surface_of_sorted[k]].color;
    float* rgba = f.iso_rgba[k + 1];
    rgba[0] = c.r;
    rgba[1] = c.g;
    rgba[2] = c.b;
    rgba[3] = 1.0f;
  }
}

// Sets up the frame of one trace and runs `run(f, clipped)` on it (the frame points into itself,
// so it lives here).
template <typename Run>
void with_frame(const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                std::span<const IsoSurface> surfaces, const TraceOptions& options, Run&& run) {
  const bool lit = !options.lights.headlight_only();
  const CameraFrame view = make_frame(camera);
  Frame f{volume,
          bvh,
          camera,
          view,
          PixelDirections(view, camera),
          {},
          volume_extent(bvh, static_cast<Vec3f>(view.eye - volume.origin)),
          {},
          {volume, view, surfaces, nullptr, options},
          false,
          {},
          local_lights(options.lights, volume.origin),
          lit,
          nullptr,
          options.lod,
          static_cast<float>(2 * view.scale_y / camera.height)};
  f.shade.surface_of_sorted = f.surface_of_sorted;
  f.smooth = options.smooth && volume.gradients.size() == volume.vertices.size() &&
             !volume.vertices.empty();
  f.isos.count = static_cast<int>(std::min<std::size_t>(surfaces.size(), kMaxIsovalues));
  std::iota(f.surface_of_sorted, f.surface_of_sorted + f.isos.count, 0);
  std::sort(f.surface_of_sorted, f.surface_of_sorted + f.isos.count,
            [&](int a, int b) { return surfaces[a].value < surfaces[b].value; });
  for (int k = 0; k < f.isos.count; ++k) f.isos.values[k] = surfaces[f.surface_of_sorted[k]].value;
  set_surface_colors(f);
  const bool clipped = !options.clip.empty();
  if (clipped) {
    f.clip = LocalClip(options.clip, volume.origin, f.extent.magnitude);
    clip_extent(f.extent, f.clip, static_cast<Vec3f>(view.eye - volume.origin));
  }
  run(f, clipped);
}

void trace_frame(const Frame& f, Framebuffer& image, bool clipped, const TraceOptions& options,
                 TraceStats* stats) {
  if (stats) *stats = {};
  const bool collect = options.collect_stats && stats;
  switch (options.packet) {
    case PacketSize::single:
      trace_with<1>(f, image, clipped, collect, stats);
      break;
    case PacketSize::p8x8:
      trace_with<8>(f, image, clipped, collect, stats);
      break;
    case PacketSize::p16x16:
      trace_with<16>(f, image, clipped, collect, stats);
      break;
    case PacketSize::p32x32:
      trace_with<32>(f, image, clipped, collect, stats);
      break;
    case PacketSize::tiled:
      trace_tiles(f, image, clipped, collect, stats);
      break;
  }
}

// The slots' layers, pixel by pixel, as a fragment image (its storage reused).
void pack(const LayerSlots& slots, const Fragment* from, FragmentImage& to, int width, int height) {
  to.width = width;
  to.height = height;
  const std::size_t pixels = to.pixel_count();
  to.begin.resize(pixels + 1);
  to.begin[0] = 0;
  for (std::size_t p = 0; p < pixels; ++p) to.begin[p + 1] = to.begin[p] + slots.count[p];
  to.fragments.resize(to.begin[pixels]);
  const auto layers = static_cast<std::size_t>(slots.max_layers);
  tbb::parallel_for(std::size_t{0}, pixels, [&](std::size_t p) {
    std::copy_n(from + p * layers, slots.count[p], to.fragments.begin() + to.begin[p]);
  });
}

}  // namespace

void trace_into(Framebuffer& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                std::span<const IsoSurface> surfaces, const TraceOptions& options,
                TraceStats* stats, std::vector<Framebuffer>* shadow_terms) {
  // The frame writes every pixel of the image and of each shadowing light's term (the
  // background too), so their storage is kept from the frame before where it has the size: a new
  // term per light and frame was 24 bytes a pixel allocated, filled and faulted in on one thread.
  const auto keep_or_make = [&](Framebuffer& target) {
    if (!has_shape(target, camera.width, camera.height))
      target = Framebuffer(camera.width, camera.height);
  };
  keep_or_make(image);
  const bool lit = !options.lights.headlight_only();
  if (shadow_terms) {
    shadow_terms->resize(lit ? static_cast<std::size_t>(options.lights.shadow_count()) : 0);
    for (Framebuffer& term : *shadow_terms) keep_or_make(term);
  }
  with_frame(volume, bvh, camera, surfaces, options, [&](Frame& f, bool clipped) {
    f.shadow_terms = shadow_terms;
    trace_frame(f, image, clipped, options, stats);
  });
}

bool has_transparency(std::span<const IsoSurface> surfaces) {
  return std::any_of(surfaces.begin(), surfaces.end(),
                     [](const IsoSurface& s) { return s.opacity < 1; });
}

void trace_layers(LayerImage& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats) {
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  LayerSlots slots;
  slots.max_layers = std::clamp(options.max_layers, 1, kMaxLayers);
  slots.shadowing = options.lights.headlight_only() ? 0 : options.lights.shadow_count();
  slots.size = pixels * static_cast<std::size_t>(slots.max_layers);
  image.slot_count.assign(pixels, 0);
  // Grown when needed, never cleared: write_layer writes every slot it counts.
  image.slots.resize(std::max(image.slots.size(), (1 + slots.shadowing) * slots.size));
  slots.count = image.slot_count.data();
  slots.color = image.slots.data();
  Framebuffer unused;  // the layers go to the slots
  with_frame(volume, bvh, camera, surfaces, options, [&](Frame& f, bool clipped) {
    for (int k = 0; k < f.isos.count; ++k)
      slots.opacity[k] = surfaces[f.surface_of_sorted[k]].opacity;
    f.layers = &slots;
    trace_frame(f, unused, clipped, options, stats);
  });
  pack(slots, slots.color, image.color, camera.width, camera.height);
  image.shadow_terms.resize(static_cast<std::size_t>(slots.shadowing));
  for (int j = 0; j < slots.shadowing; ++j)
    pack(slots, slots.shadow_term(j), image.shadow_terms[static_cast<std::size_t>(j)], camera.width,
         camera.height);
}

namespace {

// What turns a distance along a pixel's ray into its view depth. The ray runs along forward +
// a right + b up (an orthonormal frame; a and b per column and per row), so a distance along it
// is the view depth times |(1, a, b)|: per pixel an add, a square root and a division, the
// squares of a and b made once per frame (a pixel's direction normalized in double, then its dot
// with forward, was 40% of the blend of the layers).
class RayDepthScale {
 public:
  explicit RayDepthScale(const Camera& camera)
      : view_(make_frame(camera)),
        height_(camera.height),
        across_(static_cast<std::size_t>(camera.width)) {
    for (int i = 0; i < camera.width; ++i) {
      const double a = column_slope(view_, i + 0.5, camera.width);
      across_[static_cast<std::size_t>(i)] = a * a;
    }
  }

  // 1 + b^2 of row j.
  double row_term(int j) const {
    const double b = row_slope(view_, j + 0.5, height_);
    return 1.0 + b * b;
  }

  float view_depth(float distance, double row_term, int i) const {
    return static_cast<float>(distance /
                              std::sqrt(row_term + across_[static_cast<std::size_t>(i)]));
  }

 private:
  CameraFrame view_;
  int height_;
  std::vector<double> across_;
};

}  // namespace

void layer_view_depths(const FragmentImage& layers, const Camera& camera, int layer,
                       std::span<float> depth) {
  const RayDepthScale scale(camera);
  tbb::parallel_for(0, camera.height, [&](int j) {
    const double row = scale.row_term(j);
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * camera.width + i;
      const std::span<const Fragment> pixel = layers.pixel(p);
      depth[p] = static_cast<int>(pixel.size()) <= layer
                     ? std::numeric_limits<float>::infinity()
                     : scale.view_depth(pixel[layer].depth_in, row, i);
    }
  });
}

void view_depths_of_distances(const Camera& camera, std::size_t first, std::span<float> depth) {
  if (camera.width <= 0) return;
  const RayDepthScale scale(camera);
  const auto width = static_cast<std::size_t>(camera.width);
  std::size_t p = first;
  const std::size_t end = first + depth.size();
  while (p < end) {
    const auto j = static_cast<int>(p / width);
    const double row = scale.row_term(j);
    const std::size_t row_end = std::min(end, (p / width + 1) * width);
    for (; p < row_end; ++p) {
      float& d = depth[p - first];
      d = scale.view_depth(d, row, static_cast<int>(p % width));
    }
  }
}

}  // namespace tetray::render
