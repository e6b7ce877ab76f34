// Vertex renumbering after a build: vertices in the order the leaf-ordered tets first use
// them, so that the tets of a leaf, and of neighbouring leaves, read neighbouring vertices
// (Aman et al. 2022's reordering for locality, here along the BVH's own leaf order).
#pragma once

#include "render/bvh/bvh.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Renumbers volume.vertices (and color_field), rewrites the tets, drops vertices no tet uses,
// and composes volume.point_vertex. Parallel over the BVH's subtrees; the result does not
// depend on the thread count.
void renumber_vertices(TetVolume& volume, const Bvh& bvh);

}  // namespace tetray::render
