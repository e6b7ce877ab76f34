// Level of detail for the tet BVH (Knoll et al. 2009, §VI, adapted from octree volumes to the
// BVH: docs/architecture.md §9). An octree keeps coarser voxels in its inner nodes; a BVH node
// over tets keeps here the least-squares linear fit of the field over its leaves' vertices
// instead: f ~ v + g . (x - c), the gradient g and the value v at the centre c of the node's box.
// The fit reads the refit's distinct-vertex lists (about one vertex per tet, a quarter of the
// bytes walking the tets would) and needs only the vertices' moments (count, sums of x, x x^T,
// f, f x), which add from children to parents: one walk down each recorded subtree in parallel,
// then the top nodes, bitwise the same for any thread count. Nearly coplanar vertices (a singular
// covariance) give no fit, and the traversal never stops at that node. Stored as Bvh::lod_planes
// (16 bytes per node), redone after every load, refit or rebuild of a volume a LOD scene uses,
// never otherwise.
// Where the traversal stops at a node (render/trace/level_of_detail.hpp: its widest side is at
// most node_pixels pixel footprints at its distance from the eye, a test of node and camera only,
// so every packet stops at the same nodes and no seam opens), the plane f = iso cut by the node's
// box (three to six corners, at most two isopolygons; render/trace/proxy_intersect.hpp) stands in
// for the node's tets, with the tie key of its first tet. Error bound: a proxy lies inside its
// node's box, so its hit is within the node's extent of the node's tets; the surface it stands for
// may still lie elsewhere in the box (curved within it) or be missed (a fold), which
// tetray-bench --lod-study measures against the exact frame.
#pragma once

#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// planes[i] (NodePlane, bvh.hpp) for node i of the BVH, from the vertices of the leaves below
// it (the refit's lists: a vertex shared by two leaves counts in both). Parallel over the BVH's
// recorded subtrees, in the calling oneTBB arena; the result does not depend on the thread count.
void fit_node_planes(const TetVolume& volume, const Bvh& bvh, std::vector<NodePlane>& planes);

}  // namespace tetray::render
