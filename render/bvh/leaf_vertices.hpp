// The distinct vertices of each leaf, listed once after a build for the refit: a leaf's bound
// is the bound of its vertices, and its tets share most of them (about 1.05 distinct vertices
// per tet at 16 tets per leaf against 4 corners per tet), so the refit reads about a quarter
// of the vertex references and a quarter of the bytes that walking the tets would.
#pragma once

#include "render/bvh/bvh.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Fills bvh.leaf_vertex_begin and bvh.leaf_vertices from the leaf-ordered tets. Parallel; the
// lists (each in first-use order) do not depend on the thread count.
void list_leaf_vertices(const TetVolume& volume, Bvh& bvh);

}  // namespace tetray::render
