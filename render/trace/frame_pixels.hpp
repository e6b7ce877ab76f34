// What every packet of one frame shares (the Frame), and the writing of a packet's pixels into the
// image: the parts of the frame driver (trace.cpp) that the tiled driver (tile_trace.cpp) uses
// too.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "render/scene/clip_region.hpp"
#include "render/scene/shade.hpp"
#include "render/trace/level_of_detail.hpp"
#include "render/trace/ray_packet.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

// What the frustum tests need of the volume: the root's box relative to the eye (a packet whose
// frustum misses it sees only background) and the largest absolute coordinate of the eye and of
// the tets' vertices (make_packet_frustum).
struct VolumeExtent {
  Vec3f lo, hi;
  float magnitude = 0;

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
};

struct LayerSlots;  // trace.cpp: the layers of trace_layers

struct Frame {
  const TetVolume& volume;
  const Bvh& bvh;
  const Camera& camera;
  CameraFrame view;
  PixelDirections directions;
  IsoSet isos;
  VolumeExtent extent;
  int surface_of_sorted[kMaxIsovalues];
  ShadeContext shade;
  bool smooth = false;  // options.smooth with gradients to interpolate
  LocalClip clip;       // options.clip in local coordinates (used when it is not empty)
  LocalLights lights;   // used unless options.lights is a headlight alone
  bool lit = false;
  std::vector<Framebuffer>* shadow_terms = nullptr;  // one per shadowing light, or null
  LevelOfDetail lod{};                               // used when enabled
  float footprint_per_distance = 0;                  // a pixel's width at unit distance
  LayerSlots* layers = nullptr;  // trace_layers' output; null: trace_into's image
  // Without a colormap, the color of each isovalue (sorted order) at k + 1, alpha 1, and zero at
  // 0 for rays without a hit (isovalue index -1): pixels are then composed from the table, with
  // no per-pixel branch or look-up through the surfaces (write_pixels).
  bool surface_colors = false;
  alignas(16) float iso_rgba[kMaxIsovalues + 1][4] = {};
};

// One packet row's pixels, composed in the cache and then written to the frame in one go.
template <int S>
struct PixelRow {
  alignas(64) float rgba[4 * S];
  alignas(64) float depth[S];
  alignas(64) std::uint32_t hit[S];
};

// Copies `count` elements to the frame, with streaming stores where the destination lines up
// with them: they skip reading each cache line before overwriting it, which made up much of
// writing the frame (a fifth of the trace when written pixel by pixel).
template <typename T>
void write_row(T* to, const T* from, int count) {
  const std::size_t bytes = sizeof(T) * static_cast<std::size_t>(count);
  if (reinterpret_cast<std::uintptr_t>(to) % simd::kStreamBytes == 0 &&
      bytes % simd::kStreamBytes == 0) {
    simd::stream_copy(to, from, bytes);
  } else {
    std::copy_n(from, count, to);
  }
}

// Writes the packet's rows that lie in the image, each composed in the cache first by
// compose(row, columns, out).
template <int S, typename Compose>
void write_rows(const Frame& f, int x0, int y0, Framebuffer& image, Compose&& compose) {
  const int columns = std::min(S, f.camera.width - x0);
  PixelRow<S> out;
  for (int row = 0; row < S && y0 + row < f.camera.height; ++row) {
    compose(row, columns, out);
    const std::size_t p0 = image.index(x0, y0 + row);
    write_row(&image.rgba[4 * p0], out.rgba, 4 * columns);
    write_row(&image.depth[p0], out.depth, columns);
    write_row(&image.hit[p0], out.hit, columns);
  }
  simd::stream_fence();
}

// Composes the packet's pixels into `image` with the rays' light factors `light` and view depths
// `depth`: the background, or the hit shaded. The image takes it with `light` the rays' whole
// light, a shadowing light's term (shadow_terms) with that light's part.
template <int S, bool kStats>
void compose_pixels(const Frame& f, const RayPacket<S>& packet, int x0, int y0, Framebuffer& image,
                    const float* light, const float* depth, TraceStats& stats) {
  alignas(16) static constexpr float kAlphaLane[4] = {0, 0, 0, 1};
  const simd::Mask4 alpha = simd::Float4::load_aligned(kAlphaLane) != simd::Float4(0.0f);
  // Each row is composed a block of columns at a time (their rays lie side by side in the
  // packet), its depths, keys and light factors first, then each pixel's color by color_of(ray,
  // light, rgba), chosen once per packet: with the test of the table per pixel and the ray's
  // index per column, the tiled frame at 1M tets was 1-1.5% slower (alternating frames). At the
  // image's right edge the last block may reach past `columns`: those rays start with tmax = -inf
  // and hit nothing (setup_row), the row has room for them (S is a multiple of the block), and
  // write_rows copies only the first `columns` pixels.
  const auto compose = [&](auto&& color_of) {
    write_rows<S>(f, x0, y0, image, [&](int row, int columns, PixelRow<S>& out) {
      constexpr float kInf = std::numeric_limits<float>::infinity();
      constexpr int block = RayPacket<S>::kBlockColumns;
      for (int c0 = 0; c0 < columns; c0 += block) {
        const int r0 = RayPacket<S>::index(row, c0);
        alignas(16) float lit[block];
        for (int p = 0; p < block; ++p) {
          const bool hit = packet.tet[r0 + p] >= 0;
          out.depth[c0 + p] = hit ? depth[r0 + p] : kInf;
          out.hit[c0 + p] = hit ? packet.key[r0 + p] : kNoHit;
          lit[p] = hit ? light[r0 + p] : 0.0f;
          if constexpr (kStats) stats.hits += hit;
        }
        for (int p = 0; p < block; ++p) color_of(r0 + p, lit[p], &out.rgba[4 * (c0 + p)]);
      }
      if constexpr (kStats) stats.rays += static_cast<std::uint64_t>(columns);
    });
  };
  if (f.surface_colors) {
    // The table's color times the light, its alpha as it is: what shade_color forms.
    compose([&](int r, float lit, float* rgba) {
      const simd::Float4 color = simd::Float4::load_aligned(f.iso_rgba[packet.iso[r] + 1]);
      xsimd::select(alpha, color, color * simd::Float4(lit)).store_aligned(rgba);
    });
  } else {
    compose([&](int r, float lit, float* rgba) {
      if (packet.tet[r] < 0) {
        std::fill_n(rgba, 4, 0.0f);
      } else {
        shade_color(f.shade, {packet.dx[r], packet.dy[r], packet.dz[r]}, packet.tmax[r],
                    packet.tet[r], packet.iso[r], lit, rgba);
      }
    });
  }
}

// Writes the packet's pixels: the background, or the shaded hit; with several lights, also each
// shadowing light's part of the color into its own image (shadow_terms), with the pixel's depth
// and key, composed as the image is (a pixel at a time, they were a third of a lit frame's cost).
template <int S, bool kStats>
void write_pixels(const Frame& f, RayPacket<S>& packet, int x0, int y0, Framebuffer& image,
                  TraceStats& stats) {
  constexpr int n = RayPacket<S>::kRays;
  alignas(64) float light[n], depth[n];
  alignas(64) float factor[kMaxLights][n];
  const RayHits hits{packet.dx, packet.dy, packet.dz,   packet.nx,
                     packet.ny, packet.nz, packet.tmax, n};
  if (f.smooth) interpolate_normals(f.shade, hits, packet.tet, packet.nx, packet.ny, packet.nz);
  light_and_depth(f.shade, hits, light, depth);
  if (f.lit) {
    float* factors[kMaxLights];
    for (int k = 0; k < kMaxLights; ++k) factors[k] = factor[k];
    light_terms(f.shade, f.lights, hits, packet.eye, light, factors);
  }
  compose_pixels<S, kStats>(f, packet, x0, y0, image, light, depth, stats);
  if (!f.lit || f.shadow_terms == nullptr) return;
  TraceStats uncounted;  // the image's pixels counted once
  for (std::size_t j = 0; j < f.shadow_terms->size(); ++j)
    compose_pixels<S, false>(f, packet, x0, y0, (*f.shadow_terms)[j], factor[j], depth, uncounted);
}

// A packet whose frustum misses the whole volume: background, without setting up its rays.
template <int S, bool kStats>
void write_background(const Frame& f, int x0, int y0, Framebuffer& image, TraceStats& stats) {
  const auto background = [&](int, int columns, PixelRow<S>& out) {
    std::fill_n(out.rgba, 4 * columns, 0.0f);
    std::fill_n(out.depth, columns, std::numeric_limits<float>::infinity());
    std::fill_n(out.hit, columns, kNoHit);
  };
  write_rows<S>(f, x0, y0, image, [&](int row, int columns, PixelRow<S>& out) {
    background(row, columns, out);
    if constexpr (kStats) stats.rays += static_cast<std::uint64_t>(columns);
  });
  if (f.lit && f.shadow_terms) {
    for (Framebuffer& term : *f.shadow_terms) write_rows<S>(f, x0, y0, term, background);
  }
}

template <bool kClip>
using ClipNodes = std::conditional_t<kClip, ClipNodeFilter, NoNodeFilter>;
template <bool kClip>
using ClipHits = std::conditional_t<kClip, ClipHitFilter, NoHitFilter>;

// The frame's level of detail as the traversal's policy (none compiles to nothing).
template <bool kLod>
auto lod_policy(const Frame& f) {
  if constexpr (kLod) {
    return FootprintLod(f.lod, f.footprint_per_distance);
  } else {
    return NoLod{};
  }
}

// Whether a node the traversal hands to the leaf operation gives its proxy surface instead of
// its tets: a node the level of detail stopped at, or a leaf narrow enough. Without level of
// detail every node handed over is a leaf, and nothing is tested.
template <typename Lod>
bool gives_proxy(const Frame& f, const Lod& lod, const BvhNode& node, Vec3f eye) {
  if constexpr (std::is_same_v<Lod, NoLod>) {
    return false;
  } else {
    const auto index = static_cast<std::uint32_t>(&node - f.bvh.nodes.data());
    return !node.is_leaf() || lod.stops_at(index, node, eye);
  }
}

}  // namespace tetray::render
