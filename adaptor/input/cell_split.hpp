// The cells finite-element solvers write, split into the linear tets tetray renders. Linear cells
// (hexahedra, wedges, pyramids) are coned from their smallest point into the triangles of their
// other faces, each quadrilateral split by the diagonal through its own smallest point; quadratic
// cells are first cut into linear cells through their mid-edge (and face and body) nodes.
// "Smallest" is by a key per point that every rank gives the same point (a global point id, or a
// hash of its position), so two cells sharing a face split it alike, on one rank or two, and no
// crack opens (the rule and the cone are those of Dompierre et al. 1999, "How to subdivide
// pyramids, prisms and hexahedra into tetrahedra"). No point is added. Where a cell meets finer
// neighbours, its tets are bisected at the hanging nodes on its boundary (hanging_nodes.hpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tetray {

// The VTK cell types accepted (VTK's numbering; the node order of each is VTK's).
enum class CellType : std::uint8_t {
  tetra = 10,
  hexahedron = 12,
  wedge = 13,
  pyramid = 14,
  quadratic_tetra = 24,
  lagrange_tetrahedron = 71,  // order 1 (4 nodes) or 2 (10 nodes)
  lagrange_hexahedron = 72,   // order 1 (8 nodes) or 2 (27 nodes)
};

struct SplitCells {
  std::vector<std::int64_t> tets;       // 4 point indices per tet
  std::vector<std::uint64_t> tet_cell;  // the cell each tet comes from
  std::size_t hanging_midpoints = 0;    // hanging nodes found (hanging_nodes.hpp)
  std::size_t hanging_centres = 0;
  std::string error;  // empty on success
};

// The order every rank gives the points of a shared face: each point's hash of its reference
// position (xyz, 3 per point), the same whatever the rank's numbering.
std::vector<std::uint64_t> position_keys(std::span<const double> xyz);

// Splits cells [0, types.size()): cell c has VTK type types[c] and the points
// connectivity[offsets[c], offsets[c + 1]). point_keys[p] orders the points (ties: by index). A
// type tetray does not render (a polyhedron, a Lagrange cell of order 3 or more) or a node count
// that does not fit its type is an error naming the type and the first such cell. xyz (3 per
// point) places the points, to find hanging nodes; empty, none are looked for.
SplitCells split_cells(std::span<const std::uint8_t> types, std::span<const std::int64_t> offsets,
                       std::span<const std::int64_t> connectivity,
                       std::span<const std::uint64_t> point_keys, std::span<const double> xyz);

}  // namespace tetray
