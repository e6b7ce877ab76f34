// One rank's share of a cell mesh (tests/support/cell_meshes.hpp) as a solver holds it: its
// cells over only the points they use, numbered locally in a shuffled order, with the distance
// to the centre as the point field "distance" (the ball of tests/support/ball_image.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "support/cell_meshes.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {

struct RankCells {
  std::vector<double> xyz, distance;
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets{0}, connectivity;
  std::vector<std::uint8_t> ghost;  // per cell (1: another rank's), or empty

  MeshView view() const;  // as CellsView with int64 offsets and connectivity
  std::vector<FieldView> fields() const;
};

// The cells [first, last) of `mesh`, mapped onto [-1, 1]^3, their points in the order of
// `seed`'s shuffle (seed 0: the mesh's own order).
RankCells share(const CellMesh& mesh, std::size_t first, std::size_t last, unsigned seed);

// As share, with the ghost layer a solver such as deal.II gives: besides the cells [first, last),
// every other cell that shares a point with them, flagged as a ghost; and with the field
// `values` (one per point of `mesh`) instead of the distance.
RankCells share_with_ghosts(const CellMesh& mesh, std::size_t first, std::size_t last,
                            unsigned seed, const std::vector<double>& values);

// The config of one scene, "ball": the isosurface distance = `radius`, PNG only, a side x side
// image from `eye` ("[x, y, z]") looking at the centre with +y up.
std::string ball_config(const std::string& directory, double radius, const std::string& eye,
                        double fov_deg, int side);

}  // namespace tetray::testing
