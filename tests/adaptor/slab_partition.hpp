// The split-mesh tests' scene, partition, run and comparison: the gyroid with a second, linear
// field (partitioned by support/mesh_slabs.hpp), and the count of pixels two images disagree
// on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <mpi.h>

#include <span>
#include <string>

#include "scenes/box_mesh.hpp"
#include "support/mesh_slabs.hpp"
#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {

// The gyroid-twist scene at n = 10, t = 0.2 with `temperature` = c[0] + c[1] x + c[2] y + c[3] z
// at its points.
struct GyroidWithTemperature {
  GyroidTwist gyroid = make_gyroid_twist(10, 0.2);
  std::vector<double> temperature;
};
GyroidWithTemperature gyroid_with_temperature(const double (&c)[4]);

// render_step_zero of `yaml` on `part` of `scene`'s mesh (its slab's tets with their global
// ids), with the point fields `f` (the gyroid's) and `temperature`.
void render_gyroid_with_temperature(MPI_Comm comm, const std::string& yaml,
                                    const GyroidWithTemperature& scene, const Slab& part);

// The adaptor of `yaml` on `comm` renders step 0 of `mesh` and `fields` and finalizes; a failed
// call fails the test.
void render_step_zero(MPI_Comm comm, const std::string& yaml, const MeshView& mesh,
                      std::span<const FieldView> fields);

// Pixels whose RGBA differs (all of the shorter image's pixels are compared).
std::size_t differing_pixels(const PngPixels& a, const PngPixels& b);

}  // namespace tetray::testing
