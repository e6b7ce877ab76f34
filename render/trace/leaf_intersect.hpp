// The leaf operation of the traversal for every ray kind (docs/architecture.md §7): the leaf's
// tets whose own range straddles an isovalue (Wald et al. 2007, §5.2 V), culled against the
// packet's frustum, give on-the-fly isopolygons (§4.4: no cache) to the intersector.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "render/bvh/bvh.hpp"
#include "render/scene/iso_set.hpp"
#include "render/trace/isopolygon.hpp"
#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/ray_packet.hpp"
#include "render/trace/tet_straddle.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// The tet's hull lies outside the packet's frustum, behind the eye or beyond every ray's hit so
// far.
template <int S>
bool frustum_misses_tet(const RayPacket<S>& packet, const TetCorners& corners) {
  const simd::Float4 q[3] = {corners.column[0] - packet.eye.x, corners.column[1] - packet.eye.y,
                             corners.column[2] - packet.eye.z};
  return packet.frustum.misses_hull(q) || packet.frustum.outside_depths(q, packet.tmax_bound);
}

// Intersects the isopolygons of the leaf's tets that straddle an isovalue (§5.2 V) and, for
// packets, meet the packet's frustum; returns whether any ray got a new nearest hit.
template <int S, bool kStats, typename Intersector>
bool intersect_leaf(const TetVolume& volume, const IsoSet& isos, const BvhNode& leaf,
                    int first_active, Intersector& intersector, const RayPacket<S>& packet,
                    TraceStats& stats) {
  bool hit = false;
  if constexpr (kStats) stats.isorange_tests += leaf.count;
  for (std::uint64_t straddling = leaf_straddling_tets(volume, leaf.first, leaf.count, isos);
       straddling; straddling &= straddling - 1) {
    const std::uint32_t t = leaf.first + static_cast<std::uint32_t>(std::countr_zero(straddling));
    const TetCorners corners = load_corners(volume, volume.tets[t]);
    if constexpr (S > 1) {
      if (frustum_misses_tet(packet, corners)) continue;
    }
    for (int k = 0; k < isos.count; ++k) {
      const int case_index = iso_case(corners, isos.values[k]);
      if (case_index == 0 || case_index == 15) continue;
      if constexpr (kStats) ++stats.isopolygon_extractions;
      const Isopolygon poly = extract_isopolygon(corners, case_index, isos.values[k]);
      const PolygonHit id{volume.tet_ids[t], static_cast<std::int32_t>(t), k};
      hit |= intersector.intersect(poly, id, first_active);
    }
  }
  return hit;
}

}  // namespace tetray::render
