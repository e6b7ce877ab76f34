// Meshes of the cells finite-element solvers write, for the tests of the cell split: one kind of
// cell on the lattice [0, n]^3 (integer coordinates where a cell has corners, halves at quadratic
// nodes and cell centres), laid out as VTK stores cells (types, offsets, connectivity).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace tetray::testing {

using LatticePoint = std::array<double, 3>;

struct CellMesh {
  std::vector<LatticePoint> points;
  std::vector<std::uint8_t> types;  // VTK cell types
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> connectivity;
  int n = 0;

  std::set<LatticePoint> coarse_cubes;  // cubes left whole by a refining maker (their corner)

  // The index of the point at p, added when new.
  std::int64_t point(LatticePoint p);
  // The index of the point at p, which must exist.
  std::int64_t index_of(LatticePoint p) const;
  // The index of the point at p, or -1.
  std::int64_t find(LatticePoint p) const;
  void add(std::uint8_t vtk_type, const std::vector<std::int64_t>& nodes);
  // The coordinates as xyz interleaved, mapped from [0, n]^3 onto [lo, hi]^3.
  std::vector<double> xyz(double lo = 0, double hi = 1) const;

 private:
  std::map<LatticePoint, std::int64_t> index_;
};

// Adds the cells of one unit cube of the lattice, given its lowest corner.
using CellMaker = void (*)(CellMesh&, LatticePoint);

void hexahedra(CellMesh& m, LatticePoint corner);            // one hexahedron (12)
void wedges(CellMesh& m, LatticePoint corner);               // two wedges (13)
void pyramids(CellMesh& m, LatticePoint corner);             // six pyramids to the centre (14)
void quadratic_tets(CellMesh& m, LatticePoint corner);       // six 10-node tets (24 and 71)
void quadratic_hexahedra(CellMesh& m, LatticePoint corner);  // one 27-node hexahedron (72)
// Hexahedra and pyramids in the cubes of a checkerboard: a mixed mesh whose cells share
// quadrilaterals, which each side splits alone.
void hexahedra_and_pyramids(CellMesh& m, LatticePoint corner);

struct CellKind {
  const char* name;
  CellMaker make;
};
inline constexpr CellKind kCellKinds[] = {{"hexahedra", hexahedra},
                                          {"wedges", wedges},
                                          {"pyramids", pyramids},
                                          {"hexahedra and pyramids", hexahedra_and_pyramids},
                                          {"quadratic tets", quadratic_tets},
                                          {"quadratic hexahedra", quadratic_hexahedra}};

// The n^3 cubes of [0, n]^3, each filled by `make`.
CellMesh lattice(int n, CellMaker make);

// Meshes with hanging nodes, as adaptive refinement makes them: some cubes are one hexahedron,
// the others eight half-size hexahedra, whose corners hang at the middle of the coarse cubes'
// edges and faces where the two meet.
void hexahedra_refined_in_half(CellMesh& m, LatticePoint corner);      // cubes with x >= n / 2
void hexahedra_refined_alternately(CellMesh& m, LatticePoint corner);  // cubes with even i+j+k
// Cubes with x >= n / 2 or y >= n / 2: coarse faces with two edges on refinement interfaces.
void hexahedra_refined_in_an_l(CellMesh& m, LatticePoint corner);
// On [0, 4]^3: the cube at (1, 1, 1) whole, every other refined once, and the child of the cube
// at (2, 2, 1) on the whole cube's edge x = y = 2 refined again: two levels across an edge (a
// solver that balances its refinement across faces only makes such meshes).
void hexahedra_refined_twice_along_an_edge(CellMesh& m, LatticePoint corner);
inline constexpr CellKind kHangingKinds[] = {
    {"hexahedra refined in half the box", hexahedra_refined_in_half},
    {"hexahedra refined in alternate cubes", hexahedra_refined_alternately},
    {"hexahedra refined in an L", hexahedra_refined_in_an_l},
    {"hexahedra refined twice along an edge", hexahedra_refined_twice_along_an_edge}};

// The field a solver gives at hanging nodes (the hanging-node constraint of a trilinear field):
// at a point on a larger cell's edge or face, that cell's trilinear interpolant of its corners
// (the mean of the edge's two ends at its middle, of the face's four corners at its centre),
// larger cells first. `values` holds a value per point; those at hanging points are replaced.
void constrain_hanging_values(const CellMesh& m, std::vector<double>& values);

}  // namespace tetray::testing
