// Tet meshes for the mini-solver: structured grids of hexahedra, mapped to a shape (a beam, a
// thick spherical shell sector) and cut into six Kuhn tets each. The box of docs/architecture.md §6
// comes from tetray::make_box_mesh in the executable; this library only needs the Mesh type to hold
// it.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace minisolver {

using Vec3 = std::array<double, 3>;

// Faces of the parameter box a mesh was generated from. Every point carries the bits of the faces
// it lies on, so boundary conditions are given by face whatever the mapped shape.
enum Face : std::uint8_t {
  x_min = 1,
  x_max = 2,
  y_min = 4,
  y_max = 8,
  z_min = 16,
  z_max = 32,
};
inline constexpr std::uint8_t all_faces = 63;

struct Mesh {
  std::vector<double> points;          // xyz interleaved
  std::vector<std::int64_t> tets;      // 4 point indices per tet, positive orientation
  std::vector<std::uint8_t> faces;     // per point: Face bits
  std::vector<std::int32_t> material;  // per tet: index into the material table

  std::size_t point_count() const { return points.size() / 3; }
  std::size_t tet_count() const { return tets.size() / 4; }
  Vec3 point(std::size_t i) const { return {points[3 * i], points[3 * i + 1], points[3 * i + 2]}; }
};

// Points and tets of a grid of `cells` hexahedra (any of the mesh kinds), in 64 bits, so that a
// configuration can be checked before anything is allocated.
struct GridCounts {
  std::uint64_t points = 0;
  std::uint64_t tets = 0;
};
GridCounts grid_counts(std::array<int, 3> cells);

// Face bits of grid point (i, j, k) in a grid of `cells` hexahedra.
std::uint8_t grid_point_faces(std::array<int, 3> ijk, std::array<int, 3> cells);

// Maps the unit parameter cube [0,1]^3 to space.
using ParameterMap = std::function<Vec3(const Vec3& unit)>;

// cells[0]*cells[1]*cells[2] hexahedra, points numbered (k*(ny+1)+j)*(nx+1)+i, each hex cut into
// six Kuhn tets sharing its (0,0,0)-(1,1,1) diagonal; every tet oriented positive.
Mesh make_mapped_grid(std::array<int, 3> cells, const ParameterMap& map);

// The axis-aligned block [lo, hi] (a cantilever beam when long in x).
Mesh make_beam(std::array<int, 3> cells, const Vec3& lo, const Vec3& hi);

// A thick spherical shell sector: radius in [inner, outer] (z parameter), polar angle in
// [polar_min, polar_max] (y parameter), azimuth in [0, azimuth_span] (x parameter), radians.
struct ShellSpec {
  double inner_radius = 0.6;
  double outer_radius = 1.0;
  double polar_min = 0.5;
  double polar_max = 2.64;
  double azimuth_span = 4.71;
};
Mesh make_shell_sector(std::array<int, 3> cells, const ShellSpec& spec);

// Material 1 for tets whose centroid lies above `at` along `axis`, 0 below.
void split_materials(Mesh& mesh, int axis, double at);

}  // namespace minisolver
