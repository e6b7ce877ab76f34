// Meshes and the brute-force reference of the walk tests: a jittered box, its slivers (the box
// squashed a thousandfold along z), a non-convex box with tets taken out, any of them moved far
// from the origin; and every tet a ray crosses, found by testing each tet on its own.
#pragma once

#include <cstdint>
#include <vector>

#include "render/volume/tet_volume.hpp"
#include "render/walk/ray_frame.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {

struct MeshShape {
  int cells = 5;
  double jitter = 0.15;
  double squash_z = 1.0;        // z scaled by this
  double removed_fraction = 0;  // tets dropped at random: holes and a ragged boundary
  Vec3d offset{};               // added to every point
  unsigned seed = 1;
};

BoxMesh make_walk_mesh(const MeshShape& shape);
RenderScene load_walk_scene(const BoxMesh& mesh);

// A point field per vertex of `volume`'s store, from its values per caller point.
std::vector<float> per_vertex(const render::TetVolume& volume, const std::vector<double>& values);

// One tet's stretch of a ray as the brute force finds it.
struct CrossedTet {
  std::uint32_t tet;
  double t_in, t_out, f_in, f_out;
};

// Every tet of volume.tets the ray (local coordinates, t >= 0) crosses over more than
// `min_length`, ordered along the ray; each tet is tested alone in double precision.
std::vector<CrossedTet> crossed_by_brute_force(const render::TetVolume& volume, Vec3d origin,
                                               Vec3d direction, double min_length);

}  // namespace tetray::test
