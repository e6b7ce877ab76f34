// Depth peeling (trace_layers; Wald et al. 2007, §8.5, docs/architecture.md §7): the layers of
// a packet's rays written to fixed slots (write_layer, which the tiles' nearest layers use too,
// nearest_layers.hpp), and the loop that traces them one after the other for the packets of
// trace.cpp.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "render/core/fragments.hpp"
#include "render/trace/frame_pixels.hpp"
#include "render/trace/layer_filter.hpp"

namespace tetray::render {

// Depth peeling (trace_layers): each pixel's layers go to fixed slots, max_layers per pixel,
// written by the packets in parallel and packed into the LayerImage afterwards; the slots are
// the LayerImage's own (slot_count, slots), kept from frame to frame.
struct LayerSlots {
  int max_layers = 0;
  float opacity[kMaxIsovalues];   // per sorted isovalue
  std::uint8_t* count = nullptr;  // layers per pixel
  Fragment* color = nullptr;      // pixel p's layer l at p * max_layers + l
  std::size_t size = 0;           // slots of the color, and of each shadowing light after it
  int shadowing = 0;              // shadowing lights

  Fragment* shadow_term(int light) const {
    return color + static_cast<std::size_t>(light + 1) * size;
  }
};

// Layer `layer` of the packet's rays that hit: shaded as write_pixels shades a hit, as
// fragments of premultiplied color at the hit's distance.
template <int S, bool kStats>
void write_layer(const Frame& f, RayPacket<S>& packet, int x0, int y0, int layer,
                 TraceStats& stats) {
  constexpr int n = RayPacket<S>::kRays;
  alignas(64) float light[n], depth[n];
  alignas(64) float factor[kMaxLights][n];
  float* factors[kMaxLights];
  for (int k = 0; k < kMaxLights; ++k) factors[k] = factor[k];
  const RayHits hits{packet.dx, packet.dy, packet.dz,   packet.nx,
                     packet.ny, packet.nz, packet.tmax, n};
  if (f.smooth) interpolate_normals(f.shade, hits, packet.tet, packet.nx, packet.ny, packet.nz);
  light_and_depth(f.shade, hits, light, depth);
  if (f.lit) light_terms(f.shade, f.lights, hits, packet.eye, light, factors);
  LayerSlots& slots = *f.layers;
  const auto fragment = [&](int r, float light_factor, Fragment& out) {
    const float alpha = slots.opacity[packet.iso[r]];
    out.depth_in = out.depth_out = packet.tmax[r];
    out.key = packet.key[r];
    shade_color(f.shade, {packet.dx[r], packet.dy[r], packet.dz[r]}, packet.tmax[r], packet.tet[r],
                packet.iso[r], light_factor, out.rgba);
    for (int c = 0; c < 3; ++c) out.rgba[c] *= alpha;
    out.rgba[3] = alpha;
  };
  const int columns = std::min(S, f.camera.width - x0);
  for (int row = 0; row < S && y0 + row < f.camera.height; ++row) {
    if constexpr (kStats) stats.rays += layer == 0 ? static_cast<std::uint64_t>(columns) : 0;
    for (int c = 0; c < columns; ++c) {
      const int r = RayPacket<S>::index(row, c);
      if (packet.tet[r] < 0) continue;
      if constexpr (kStats) ++stats.hits;
      const std::size_t p = static_cast<std::size_t>(y0 + row) * f.camera.width + x0 + c;
      const std::size_t slot = p * static_cast<std::size_t>(slots.max_layers) + layer;
      slots.count[p] = static_cast<std::uint8_t>(layer + 1);
      fragment(r, light[r], slots.color[slot]);
      for (int j = 0; j < slots.shadowing; ++j)
        fragment(r, factor[j][r], slots.shadow_term(j)[slot]);
    }
  }
}

// Readies the packet for the layer after the one it holds: rays whose hit is transparent are
// traced again with that hit as the bound to pass, the others (no hit, or an opaque one) hit
// nothing more. Returns how many rays go on.
template <int S>
int next_layer(const Frame& f, RayPacket<S>& packet, float* previous_t,
               std::uint32_t* previous_key) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  int going = 0;
  for (int r = 0; r < RayPacket<S>::kRays; ++r) {
    const bool on = packet.tet[r] >= 0 && f.layers->opacity[packet.iso[r]] < 1;
    previous_t[r] = packet.tmax[r];
    previous_key[r] = packet.key[r];
    packet.tmax[r] = on ? kInf : -kInf;
    packet.key[r] = kNoHit;
    packet.tet[r] = -1;
    going += on;
  }
  packet.tmax_bound = kInf;
  packet.rays_without_hit = going;
  reset_batch_bounds(packet);
  return going;
}

// The packet's layers after its first hit: the same origin and frustum, and filters passing
// only hits after each ray's previous layer; trace_again(node_filter, hit_filter) traces the
// packet's rays once more with them (the one traversal, or a tile's bin again).
template <int S, bool kStats, bool kClip, typename TraceAgain>
void peel_layers(const Frame& f, RayPacket<S>& packet, int x0, int y0, TraceStats& stats,
                 TraceAgain&& trace_again) {
  alignas(64) float previous_t[RayPacket<S>::kRays];
  alignas(64) std::uint32_t previous_key[RayPacket<S>::kRays];
  const AfterLayerNodeFilter<ClipNodes<kClip>> nodes{ClipNodes<kClip>(f.clip), previous_t};
  const AfterLayerFilter<ClipHits<kClip>> hits{ClipHits<kClip>(f.clip), previous_t, previous_key};
  for (int layer = 0; layer + 1 < f.layers->max_layers; ++layer) {
    write_layer<S, kStats>(f, packet, x0, y0, layer, stats);
    const int going = next_layer(f, packet, previous_t, previous_key);
    if (going == 0) return;
    if constexpr (kStats) stats.rays += static_cast<std::uint64_t>(going);
    trace_again(nodes, hits);
  }
  write_layer<S, kStats>(f, packet, x0, y0, f.layers->max_layers - 1, stats);
}

}  // namespace tetray::render
