// Level of detail for the tet BVH (Knoll et al. 2009, §VI, adapted from octree volumes to the
// BVH: docs/architecture.md §9). An octree keeps coarser voxels in its inner nodes; a BVH node
// over tets keeps here the linear fit of the field over its tets instead: the volume-weighted
// mean gradient and the fit's value at the centre of the node's box. Where the traversal stops
// at a node (the node is narrower than the pixel footprint allows), the isosurface of that
// plane within the node's box stands in for the node's tets. Computed only for scenes that ask
// for level of detail, after each refit.
#pragma once

#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// NodePlane (bvh.hpp) planes[i] for node i of the BVH, bottom-up: a leaf from its tets, an inner
// node from its two children. Parallel over the BVH's recorded subtrees (as the refit), in the
// calling oneTBB arena; the result does not depend on the thread count.
void fit_node_planes(const TetVolume& volume, const Bvh& bvh, std::vector<NodePlane>& planes);

}  // namespace tetray::render
