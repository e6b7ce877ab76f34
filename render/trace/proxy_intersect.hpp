// The leaf operation of the traversal at a node the level of detail stopped at
// (level_of_detail.hpp), beside the exact one of leaf_intersect.hpp: the node's proxy
// isopolygons go to the same intersector.
#pragma once

#include <cstdint>

#include "render/bvh/bvh.hpp"
#include "render/scene/iso_set.hpp"
#include "render/trace/isopolygon_intersect.hpp"
#include "render/trace/level_of_detail.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Calls visit(polygon, hit) for the proxy isopolygons of every isovalue the node's range
// straddles. A hit keeps the tet id of the node's first tet as its tie key, and that tet for
// shading.
template <typename Visit>
void for_each_proxy(const TetVolume& volume, const Bvh& bvh, const LevelOfDetail& lod,
                    const IsoSet& isos, const BvhNode& node, Visit&& visit) {
  const NodePlane& plane = lod.planes[static_cast<std::size_t>(&node - bvh.nodes.data())];
  const BvhNode* leaf = &node;
  while (!leaf->is_leaf()) leaf = &bvh.nodes[leaf->first];
  const std::int32_t tet = static_cast<std::int32_t>(leaf->first);
  for (int k = 0; k < isos.count; ++k) {
    if (!(node.bounds.lo[3] < isos.values[k] && isos.values[k] <= node.bounds.hi[3])) continue;
    Isopolygon polys[2];
    const int count = proxy_isopolygons(node.bounds, plane, isos.values[k], polys);
    for (int j = 0; j < count; ++j) visit(polys[j], PolygonHit{volume.tet_ids[tet], tet, k});
  }
}

// The packet's rays against the node's proxy isopolygons. Returns whether any ray got a new
// nearest hit.
template <typename Intersector>
bool intersect_proxy(const TetVolume& volume, const Bvh& bvh, const LevelOfDetail& lod,
                     const IsoSet& isos, const BvhNode& node, int first_active,
                     Intersector& intersector) {
  bool hit = false;
  for_each_proxy(volume, bvh, lod, isos, node, [&](const Isopolygon& poly, const PolygonHit& id) {
    hit |= intersector.intersect(poly, id, first_active);
  });
  return hit;
}

}  // namespace tetray::render
