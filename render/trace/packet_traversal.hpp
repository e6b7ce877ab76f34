// Packet traversal of the implicit BVH (Wald et al. 2007, §5.2), written once and templated on the
// packet (a RayPacket of any size, or a Tile: a frustum without rays) and on what a leaf does
// (docs/architecture.md §7), in the order Wald et al. 2007 give:
//   I   implicit culling: a node whose scalar range straddles no isovalue is skipped, and a node
//       with one active child descends into it without any geometric test;
//   II  speculative first-active descent: if the first active ray hits the node, descend;
//   III else an interval-arithmetic frustum test rejects nodes the whole packet misses;
//   IV  else rays are tested in order until one hits; those before it become inactive for the
//       subtree (first-active tracking).
// Leaves get the same geometric test, then the leaf operation runs from the first active ray. A
// tile has no rays: its geometric test is its frustum's (step III alone, exact for the four
// planes), and every node it reaches is active from ray 0.
// A node filter (render/scene/clip_region.hpp) may discard further subtrees alongside the iso-range
// test, and gives the distance from which each ray's box test starts (a transparent layer's rays
// start at the previous layer, layer_filter.hpp); the default one discards none, starts at the
// eye and compiles to nothing. A level-of-detail policy (level_of_detail.hpp) may stop the
// descent at an inner node, which then goes to the leaf operation as it is; the default one
// never stops and compiles to nothing.
//
// The clip region's node test keeps a margin of 1e-5 of the coordinate magnitude, so only the hit
// test decides and the image does not depend on the BVH. Shadow rays (shadow_rays.cpp) are packets
// too: rays towards a point light start at the light and end short of the hit points, so they share
// an origin; the traversal's interval test bounds them and, with no corner rays, the tet and
// isopolygon frustum tests get four planes around the rays' mean direction that bound every ray's
// slopes (packet_frustum.hpp, make_direction_frustum; the row restriction of primary rays is off).
// A leaf operation that returns true ends the walk, which the any-hit leaf does once every ray is
// occluded. Rays towards a directional light share no origin and go one by one.
//
// Transparency (Wald et al. 2007, §8.5) is one more hit filter, not a copy of the walk: the rays of
// a packet whose hit is transparent are traced again from the same origin and frustum with an
// after-layer filter (layer_filter.hpp) that keeps only hits strictly after the previous layer's
// (distance, key) in the tie order, so a hit at a shared edge is peeled exactly once; peeling stops
// at an opaque layer or max_layers. Each layer is shaded as a first hit and becomes a zero-length
// fragment at its ray distance (render/core/fragments.hpp), so the nearest layers of each rank
// contain the nearest of all ranks together. The layers go into max_layers slots per pixel, packed
// into the fragment image after the frame; the slots belong to the LayerImage and are kept from
// frame to frame (allocating and clearing them per frame cost more than tracing the layers).
#pragma once

#include <cstdint>
#include <span>
#include <type_traits>

#include "render/bvh/bvh.hpp"
#include "render/scene/clip_region.hpp"
#include "render/scene/iso_set.hpp"
#include "render/trace/isopolygon.hpp"
#include "render/trace/level_of_detail.hpp"
#include "render/trace/ray_packet.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

// Robust slab test (Ize, "Robust BVH ray traversal", 2013): the far distance grows by
// 1 + 2 gamma(3), so rounding never lets a ray miss a box around a surface it hits.
inline constexpr float kRobustFar = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);

template <typename Packet, bool kStats, typename NodeFilter = NoNodeFilter, typename Lod = NoLod>
class PacketTraversal {
 public:
  PacketTraversal(const Bvh& bvh, const IsoSet& isos, Packet& packet, TraceStats& stats,
                  NodeFilter filter = {}, Lod lod = {})
      : bvh_(bvh), isos_(isos), packet_(packet), stats_(stats), filter_(filter), lod_(lod) {}

  // Runs the traversal; leaf(node, first_active) intersects a leaf's tets. A leaf operation
  // that returns bool ends the traversal by returning true (any-hit rays: all are done).
  template <typename LeafOp>
  void run(LeafOp&& leaf) {
    if (bvh_.empty() || !range_active(bvh_.nodes[0])) return;
    struct Entry {
      std::uint32_t node;
      int first_active;
    };
    Entry stack[kStackSize];
    int top = 0;
    std::uint32_t node = 0;
    int active = geometric_test(bvh_.nodes[0], 0);
    for (;;) {
      if (active >= 0) {
        descend(node, active, [&](std::uint32_t far, int fa) { stack[top++] = {far, fa}; });
        if (active >= 0) {
          if constexpr (std::is_same_v<decltype(leaf(bvh_.nodes[node], active)), bool>) {
            if (leaf(bvh_.nodes[node], active)) return;
          } else {
            leaf(bvh_.nodes[node], active);
          }
        }
      }
      if (top == 0) return;
      --top;
      node = stack[top].node;
      active = geometric_test(bvh_.nodes[node], stack[top].first_active);
    }
  }

 private:
  static constexpr int kStackSize = 128;  // the builders bound the depth well below this
  static constexpr bool kTile = Packet::kRays == 0;

  // Interval arithmetic over the packet's inverse directions: every ray's entry distance is at
  // least `enter` and its exit at most `leave`; rounding is monotonic, so the bounds hold for
  // the per-ray float computations too.
  bool frustum_misses(const Bounds4& b) const {
    float enter = 0, leave = std::numeric_limits<float>::infinity();
    const float e[3] = {packet_.eye.x, packet_.eye.y, packet_.eye.z};
    for (int a = 0; a < 3; ++a) {
      if (packet_.inv_straddles[a]) continue;
      const bool positive = packet_.inv_lo[a] >= 0;
      const float near_plane = (positive ? b.lo[a] : b.hi[a]) - e[a];
      const float far_plane = (positive ? b.hi[a] : b.lo[a]) - e[a];
      enter =
          std::max(enter, std::min(near_plane * packet_.inv_lo[a], near_plane * packet_.inv_hi[a]));
      leave =
          std::min(leave, std::max(far_plane * packet_.inv_lo[a], far_plane * packet_.inv_hi[a]));
    }
    return enter > leave * kRobustFar || enter > packet_.tmax_bound;
  }

  bool range_active(const BvhNode& n) {
    if constexpr (kStats) ++stats_.isorange_tests;
    return isos_.straddled_by(n.bounds.lo[3], n.bounds.hi[3]) && !filter_.discards(n.bounds);
  }

  // Walks down from `node` to a leaf, or to a node the level of detail stops at (updating node
  // and active), pushing far children of bifurcations; active becomes -1 when the walk ends
  // without a node to intersect.
  template <typename Push>
  void descend(std::uint32_t& node, int& active, Push&& push) {
    while (!bvh_.nodes[node].is_leaf() && !lod_.stops_at(node, bvh_.nodes[node], packet_.eye)) {
      const std::uint32_t first = bvh_.nodes[node].first;
      const bool a0 = range_active(bvh_.nodes[first]), a1 = range_active(bvh_.nodes[first + 1]);
      if (!a0 && !a1) {
        active = -1;
        return;
      }
      if (a0 != a1) {  // speculative: the single active child needs no geometric test
        node = a0 ? first : first + 1;
        continue;
      }
      const bool left_first = near_child_is_first(first);
      const std::uint32_t far = left_first ? first + 1 : first;
      node = left_first ? first : first + 1;
      prefetch_children(far);
      prefetch_children(node);
      push(far, active);
      active = geometric_test(bvh_.nodes[node], active);
      if (active < 0) return;
    }
  }

  // Asks for the cache lines of an inner node's children ahead of use: node visits wait on
  // memory, and the geometric test of the near child, or the whole near subtree for the far
  // one, runs meanwhile. (Asking for a leaf's tets the same way gained nothing; the tiles ask
  // for them one leaf ahead of its set-up instead, tile_trace.cpp.)
  void prefetch_children(std::uint32_t node) const {
    const BvhNode& n = bvh_.nodes[node];
    if (n.is_leaf()) return;
    __builtin_prefetch(&bvh_.nodes[n.first]);
    __builtin_prefetch(&bvh_.nodes[n.first + 1].count);
  }

  // Front-to-back order along the packet's mean direction.
  bool near_child_is_first(std::uint32_t first) const {
    const Bounds4& a = bvh_.nodes[first].bounds;
    const Bounds4& b = bvh_.nodes[first + 1].bounds;
    const Vec3f d = mean_direction();
    float along = 0;
    for (int k = 0; k < 3; ++k) along += d[k] * ((b.lo[k] + b.hi[k]) - (a.lo[k] + a.hi[k]));
    return along >= 0;
  }

  // The packet's middle ray, or the direction through a tile's center.
  Vec3f mean_direction() const {
    if constexpr (kTile) {
      return packet_.center_direction;
    } else {
      constexpr int mid = Packet::index(Packet::kSide / 2, Packet::kSide / 2);
      return {packet_.dx[mid], packet_.dy[mid], packet_.dz[mid]};
    }
  }

  // Index of the first ray at or after `first_active` that hits the node's box, or -1 (for a
  // tile: 0 where its frustum meets the box).
  int geometric_test(const BvhNode& n, int first_active) {
    if constexpr (kStats) ++stats_.packet_box_tests;
    if constexpr (kTile) {
      return packet_.misses(n.bounds) ? -1 : 0;
    } else {
      return first_ray_hit(n, first_active);
    }
  }

  int first_ray_hit(const BvhNode& n, int first_active) {
    using F = typename Packet::Lanes::F;
    constexpr int W = Packet::kLaneWidth;
    if (ray_hits<float>(n.bounds, first_active)) return first_active;
    if (frustum_misses(n.bounds)) return -1;
    for (int base = (first_active + 1) / W * W; base < Packet::kRays; base += W) {
      std::uint64_t hits = simd::bits(ray_hits<F>(n.bounds, base));
      hits &= ~std::uint64_t{0} << std::max(0, first_active + 1 - base);
      if (hits) return base + std::countr_zero(hits);
    }
    return -1;
  }

  // Slab test of the W (or one) rays starting at r.
  template <typename V>
  auto ray_hits(const Bounds4& b, int r) {
    if constexpr (kStats) stats_.ray_box_tests += sizeof(V) / sizeof(float);
    const Vec3f e = packet_.eye;
    const V ix = simd::load(packet_.ix + r, V{}), iy = simd::load(packet_.iy + r, V{}),
            iz = simd::load(packet_.iz + r, V{});
    const V tx0 = (b.lo[0] - e.x) * ix, tx1 = (b.hi[0] - e.x) * ix;
    const V ty0 = (b.lo[1] - e.y) * iy, ty1 = (b.hi[1] - e.y) * iy;
    const V tz0 = (b.lo[2] - e.z) * iz, tz1 = (b.hi[2] - e.z) * iz;
    using simd::vmax, simd::vmin;
    const V near =
        vmax(vmax(vmin(tx0, tx1), vmin(ty0, ty1)), vmax(vmin(tz0, tz1), filter_.ray_tmin(r, V{})));
    const V far = vmin(vmin(vmax(tx0, tx1), vmax(ty0, ty1)), vmax(tz0, tz1)) * kRobustFar;
    return near <= vmin(far, simd::load(packet_.tmax + r, V{}));
  }

  const Bvh& bvh_;
  const IsoSet& isos_;
  Packet& packet_;
  TraceStats& stats_;
  [[no_unique_address]] NodeFilter filter_;
  [[no_unique_address]] Lod lod_;
};

}  // namespace tetray::render
