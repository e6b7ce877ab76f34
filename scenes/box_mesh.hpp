// A structured tet mesh generator for coupling tests and benchmarks (docs/architecture.md §6): the
// box [lo, hi] split into nx*ny*nz hexahedra, each into 6 tets by the Kuhn/Freudenthal subdivision
// (all six share the hex diagonal from its (0,0,0) to its (1,1,1) corner), with optional
// deterministic jitter of interior points that keeps every tet positive.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace tetray {

struct BoxMeshSpec {
  std::array<int, 3> cells{8, 8, 8};
  std::array<double, 3> lo{-1, -1, -1};
  std::array<double, 3> hi{1, 1, 1};
  double jitter =
      0.0;  // amplitude as a fraction of the cell size (docs/architecture.md §6 uses 0.15)
};

struct BoxMesh {
  std::vector<double> points;      // xyz interleaved, (nx+1)(ny+1)(nz+1) points
  std::vector<std::int64_t> tets;  // 4 per tet, 6 nx ny nz tets, positive orientation
  std::array<int, 3> cells{};

  std::size_t point_count() const { return points.size() / 3; }
  std::size_t tet_count() const { return tets.size() / 4; }
  // Index of grid point (i, j, k), in 64 bits (cells + 1 overflows int at INT_MAX cells).
  std::int64_t point_index(int i, int j, int k) const {
    return (static_cast<std::int64_t>(k) * (std::int64_t{cells[1]} + 1) + j) *
               (std::int64_t{cells[0]} + 1) +
           i;
  }
};

// Needs cells >= 1 on every axis and memory for the mesh: (nx+1)(ny+1)(nz+1) points of 24 bytes
// and 6 nx ny nz tets of 32 bytes; a caller taking cells from a user checks the sizes first.
BoxMesh make_box_mesh(const BoxMeshSpec& spec);

// The gyroid-twist benchmark scene of docs/architecture.md §6 at resolution n and time t: the
// jittered box mesh of [-1,1]^3 rotated about z by 0.3 z sin(t), and the field at the deformed
// positions.
struct GyroidTwist {
  BoxMesh mesh;               // points already deformed for time t
  std::vector<double> field;  // one value per point
};
GyroidTwist make_gyroid_twist(int n, double t);
void deform_gyroid_twist(const BoxMesh& reference, double t, std::vector<double>& points,
                         std::vector<double>& field);

}  // namespace tetray
