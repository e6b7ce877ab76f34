// Per-vertex gradients of the isosurface field for smooth shading: the gradient of a linear tet
// is constant, so a normal from it alone is flat per isopolygon and shows the mesh as facets.
// Averaging the tets' gradients at each vertex (weighted by tet volume) and interpolating them
// barycentrically at the hit gives a normal that varies continuously across shared faces.
#pragma once

#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Fills volume.gradients, one per vertex: the volume-weighted mean of the gradients of the tets
// that use the vertex (zero for a vertex of flat tets only).
void compute_vertex_gradients(TetVolume& volume);

}  // namespace tetray::render
