// Meshes of the cells finite-element solvers write, for the tests of the cell split: one kind of
// cell on the lattice [0, n]^3 (integer coordinates where a cell has corners, halves at quadratic
// nodes and cell centres), laid out as VTK stores cells (types, offsets, connectivity).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace tetray::testing {

using LatticePoint = std::array<double, 3>;

struct CellMesh {
  std::vector<LatticePoint> points;
  std::vector<std::uint8_t> types;  // VTK cell types
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> connectivity;
  int n = 0;

  // The index of the point at p, added when new.
  std::int64_t point(LatticePoint p);
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

}  // namespace tetray::testing
