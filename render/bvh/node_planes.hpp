// Level of detail for the tet BVH (Knoll et al. 2009, §VI, adapted from octree volumes to the
// BVH: docs/architecture.md §9). An octree keeps coarser voxels in its inner nodes; a BVH node
// over tets keeps here the least-squares linear fit of the field over its leaves' vertices
// instead: the gradient and the value at the centre of the node's box. Where the traversal stops
// at a node (the node is narrower than the pixel footprint allows), the isosurface of that
// plane within the node's box stands in for the node's tets. Computed only for scenes that ask
// for level of detail, after each refit.
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
