// The split-mesh tests' partition, run and comparison: a rank's share of a mesh in [-1, 1]^3 as the
// tets whose centroid's x falls in its slab (with their indices in the whole mesh as global
// ids), and the count of pixels two images disagree on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <mpi.h>

#include <span>
#include <string>

#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"
#include "tools/scenes/box_mesh.hpp"

namespace tetray::testing {

struct Slab {
  std::vector<std::int64_t> tets;  // 4 per tet, the whole mesh's point numbers
  std::vector<std::int64_t> ids;   // each tet's index in the whole mesh
};

// Slab `rank` of `ranks` equal slabs of x in [-1, 1] (clamped at the ends).
Slab x_slab(const BoxMesh& mesh, int rank, int ranks);

// The adaptor of `yaml` on `comm` renders step 0 of `mesh` and `fields` and finalizes; a failed
// call fails the test.
void render_step_zero(MPI_Comm comm, const std::string& yaml, const MeshView& mesh,
                      std::span<const FieldView> fields);

// Pixels whose RGBA differs (all of the shorter image's pixels are compared).
std::size_t differing_pixels(const PngPixels& a, const PngPixels& b);

}  // namespace tetray::testing
