// Transparent layers in one test of a tile packet's bin. Depth peeling (layer_peeling.hpp) tests
// the bin again for each layer, so a ray meets every polygon of its bin once per layer it peels
// (1M tets, two surfaces, 4 layers: 24M ray-polygon tests against the opaque frame's 4M). Here
// each ray keeps its max_layers nearest hits while the bin is tested once (Wald et al. 2007, §8.5:
// the cost of transparency then grows with the hits kept, not with the layers traced), and the
// layers are written one after the other as the peeling writes them.
//
// The order is the peeling's (layer_filter.hpp): by distance, then by the smaller tie key, and a
// hit at the distance and key of one kept is that same layer (the peeling passes only hits
// strictly after the layer before). Of two such hits the one tested first stays, as in the
// peeling, where the later one never wins. A ray's layers stop after its first opaque one, as the
// peeling stops tracing it. So the layers are those of the peeling, bit for bit.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "render/core/simd.hpp"
#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/layer_peeling.hpp"

namespace tetray::render {

template <int S>
class NearestLayers {
 public:
  using Packet = RayPacket<S>;
  static constexpr int kRays = Packet::kRays, W = Packet::kLaneWidth;
  static_assert(W == simd::kWidth, "a packet of whole lane batches");

  // No hit kept, `layers` (1..kMaxLayers) at most per ray.
  void reset(int layers) {
    layers_ = layers;
    for (int b = 0; b < Packet::kBatches; ++b)
      for (int l = 0; l < layers; ++l) std::fill_n(slots_[b][l].t, W, kNone);
  }

  // Keeps the hits of the polygon (`id`, plane normal `normal`) in the lane batch at `base`: the
  // lanes of `ahead`, at distances `t`.
  void insert(int base, simd::Mask ahead, simd::Floats t, const PolygonHit& id, Vec3f normal) {
    using simd::Floats, simd::Ints, simd::Mask;
    Floats carry_t = simd::select(ahead, t, Floats(kNone));
    Ints carry_key(ordered(id.key)), carry_tet(id.tet), carry_iso(id.iso);
    Floats carry_nx(normal.x), carry_ny(normal.y), carry_nz(normal.z);
    for (int l = 0; l < layers_; ++l) {
      if (!simd::any(carry_t < Floats(kNone))) return;
      Slot& slot = slots_[base / W][l];
      const Floats kept_t = Floats::load_aligned(slot.t);
      const Ints kept_key = Ints::load_aligned(slot.key);
      const Mask same_t = carry_t == kept_t;
      // A hit kept already: the carry is dropped.
      carry_t =
          simd::select(same_t & xsimd::bool_cast(carry_key == kept_key), Floats(kNone), carry_t);
      const Mask before = (carry_t < kept_t) | (same_t & xsimd::bool_cast(carry_key < kept_key));
      const auto lanes = xsimd::bool_cast(before);
      const auto swap = [&](auto& carry, auto* row, auto mask) {
        using Batch = std::remove_reference_t<decltype(carry)>;
        const Batch kept = Batch::load_aligned(row);
        xsimd::select(mask, carry, kept).store_aligned(row);
        carry = xsimd::select(mask, kept, carry);
      };
      swap(carry_t, slot.t, before);
      swap(carry_key, slot.key, lanes);
      swap(carry_tet, slot.tet, lanes);
      swap(carry_iso, slot.iso, lanes);
      swap(carry_nx, slot.nx, before);
      swap(carry_ny, slot.ny, before);
      swap(carry_nz, slot.nz, before);
    }
  }

  // Puts layer l of the rays in `going` into the packet's hit (tmax, key, tet, iso, normal), and
  // no hit into the others; returns how many have one.
  int load_layer(int l, const bool* going, Packet& packet) const {
    int count = 0;
    for (int r = 0; r < kRays; ++r) {
      packet.tmax[r] = kNone;
      packet.key[r] = kNoHit;
      packet.tet[r] = -1;
      const Slot& slot = slots_[r / W][l];
      const int k = r % W;
      if (!going[r] || !(slot.t[k] < kNone)) continue;
      packet.tmax[r] = slot.t[k];
      packet.key[r] = unordered(slot.key[k]);
      packet.tet[r] = slot.tet[k];
      packet.iso[r] = slot.iso[k];
      packet.nx[r] = slot.nx[k];
      packet.ny[r] = slot.ny[k];
      packet.nz[r] = slot.nz[k];
      ++count;
    }
    return count;
  }

 private:
  static constexpr float kNone = std::numeric_limits<float>::infinity();
  // Keys with the sign bit flipped: the signed order of the lanes is the keys' unsigned order.
  static std::int32_t ordered(std::uint32_t key) {
    return static_cast<std::int32_t>(key ^ 0x80000000u);
  }
  static std::uint32_t unordered(std::int32_t key) {
    return static_cast<std::uint32_t>(key) ^ 0x80000000u;
  }

  // One layer of a lane batch's rays. A batch's layers lie side by side: an insertion walks down
  // them (laid out per layer across the packet, their rows 4 KiB apart, the stores of one
  // insertion met in the same cache sets, and the frame was no faster than peeling).
  struct Slot {
    static constexpr std::size_t kBatchBytes = sizeof(float) * W;  // a lane batch, aligned
    alignas(kBatchBytes) float t[W];                               // kNone past the ray's hits
    alignas(kBatchBytes) std::int32_t key[W];
    alignas(kBatchBytes) std::int32_t tet[W];
    alignas(kBatchBytes) std::int32_t iso[W];
    alignas(kBatchBytes) float nx[W];
    alignas(kBatchBytes) float ny[W];
    alignas(kBatchBytes) float nz[W];
  };

  // No padding: the slots hold 28 bytes per ray and layer, 458,752 bytes for a packet of 32 x 32
  // at kMaxLayers, whatever the lane width.
  static_assert(sizeof(Slot) == 7 * Slot::kBatchBytes);

  int layers_ = 0;
  Slot slots_[Packet::kBatches][kMaxLayers];
};

// Writes the kept layers as peel_layers writes the peeled ones (write_layer), a ray's up to its
// first opaque one.
template <int S, bool kStats>
void write_nearest_layers(const Frame& f, RayPacket<S>& packet, const NearestLayers<S>& nearest,
                          int x0, int y0, TraceStats& stats) {
  constexpr int n = RayPacket<S>::kRays;
  bool going[n];
  for (int r = 0; r < n; ++r) going[r] = packet.tmax[r] != -std::numeric_limits<float>::infinity();
  for (int layer = 0; layer < f.layers->max_layers; ++layer) {
    const int hits = nearest.load_layer(layer, going, packet);
    if (layer > 0 && hits == 0) return;
    if constexpr (kStats) stats.rays += layer > 0 ? static_cast<std::uint64_t>(hits) : 0;
    write_layer<S, kStats>(f, packet, x0, y0, layer, stats);
    for (int r = 0; r < n; ++r)
      going[r] = packet.tet[r] >= 0 && f.layers->opacity[packet.iso[r]] < 1;
  }
}

}  // namespace tetray::render
