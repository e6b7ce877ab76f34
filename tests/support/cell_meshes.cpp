#include "support/cell_meshes.hpp"

#include <vtkCellType.h>
#include <vtkLagrangeHexahedron.h>
#include <vtkNew.h>

#include <cmath>
#include <stdexcept>

namespace tetray::testing {
namespace {

std::array<std::int64_t, 8> cube_corners(CellMesh& m, LatticePoint o) {
  std::array<std::int64_t, 8> c{};
  const int dx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dy[8] = {0, 0, 1, 1, 0, 0, 1, 1},
            dz[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  for (int k = 0; k < 8; ++k) c[k] = m.point({o[0] + dx[k], o[1] + dy[k], o[2] + dz[k]});
  return c;
}

LatticePoint mid(const CellMesh& m, std::int64_t a, std::int64_t b) {
  const LatticePoint& p = m.points[a];
  const LatticePoint& q = m.points[b];
  return {0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])};
}

}  // namespace

std::int64_t CellMesh::point(LatticePoint p) {
  const auto found = index_.find(p);
  if (found != index_.end()) return found->second;
  points.push_back(p);
  return index_[p] = static_cast<std::int64_t>(points.size() - 1);
}

std::int64_t CellMesh::find(LatticePoint p) const {
  const auto found = index_.find(p);
  return found == index_.end() ? -1 : found->second;
}

std::int64_t CellMesh::index_of(LatticePoint p) const {
  const auto found = index_.find(p);
  if (found == index_.end()) throw std::out_of_range("no lattice point there");
  return found->second;
}

void CellMesh::add(std::uint8_t vtk_type, const std::vector<std::int64_t>& nodes) {
  types.push_back(vtk_type);
  connectivity.insert(connectivity.end(), nodes.begin(), nodes.end());
  offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
}

std::vector<double> CellMesh::xyz(double lo, double hi) const {
  std::vector<double> out;
  out.reserve(3 * points.size());
  for (const LatticePoint& p : points) {
    for (double c : p) out.push_back(lo + (hi - lo) * c / n);
  }
  return out;
}

void hexahedra(CellMesh& m, LatticePoint o) {
  const auto c = cube_corners(m, o);
  m.add(VTK_HEXAHEDRON, {c.begin(), c.end()});
}

void wedges(CellMesh& m, LatticePoint o) {
  const auto c = cube_corners(m, o);
  m.add(VTK_WEDGE, {c[0], c[1], c[2], c[4], c[5], c[6]});
  m.add(VTK_WEDGE, {c[0], c[2], c[3], c[4], c[6], c[7]});
}

void pyramids(CellMesh& m, LatticePoint o) {
  const auto c = cube_corners(m, o);
  const std::int64_t centre = m.point({o[0] + 0.5, o[1] + 0.5, o[2] + 0.5});
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& f : faces) m.add(VTK_PYRAMID, {c[f[0]], c[f[1]], c[f[2]], c[f[3]], centre});
}

void hexahedra_and_pyramids(CellMesh& m, LatticePoint o) {
  const bool even = (static_cast<int>(o[0] + o[1] + o[2]) % 2) == 0;
  (even ? hexahedra : pyramids)(m, o);
}

// Six Kuhn tets of 10 nodes each (VTK order: corners, then edges 01, 12, 02, 03, 13, 23).
void quadratic_tets(CellMesh& m, LatticePoint o) {
  const auto c = cube_corners(m, o);
  const int kuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                          {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  for (int t = 0; t < 6; ++t) {
    std::vector<std::int64_t> nodes;
    for (int v : kuhn[t]) nodes.push_back(c[v]);
    for (const auto& e : edges) nodes.push_back(m.point(mid(m, nodes[e[0]], nodes[e[1]])));
    m.add(t % 2 ? VTK_QUADRATIC_TETRA : VTK_LAGRANGE_TETRAHEDRON, nodes);
  }
}

// One 27-node Lagrange hexahedron, its nodes ordered by VTK's own vtkLagrangeHexahedron.
void quadratic_hexahedra(CellMesh& m, LatticePoint o) {
  vtkNew<vtkLagrangeHexahedron> cell;
  cell->SetOrder(2, 2, 2);
  std::vector<std::int64_t> nodes(27);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        nodes[cell->PointIndexFromIJK(i, j, k)] =
            m.point({o[0] + 0.5 * i, o[1] + 0.5 * j, o[2] + 0.5 * k});
      }
  m.add(VTK_LAGRANGE_HEXAHEDRON, nodes);
}

namespace {

// A hexahedron of side `side` at lattice corner o, VTK's corner order.
void add_hexahedron(CellMesh& m, LatticePoint o, double side) {
  const int dx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dy[8] = {0, 0, 1, 1, 0, 0, 1, 1},
            dz[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  std::vector<std::int64_t> nodes;
  for (int k = 0; k < 8; ++k) {
    nodes.push_back(m.point({o[0] + side * dx[k], o[1] + side * dy[k], o[2] + side * dz[k]}));
  }
  m.add(VTK_HEXAHEDRON, nodes);
}

// Eight hexahedra of half the side.
void refined_cube(CellMesh& m, LatticePoint o) {
  for (int child = 0; child < 8; ++child) {
    add_hexahedron(
        m, {o[0] + 0.5 * (child & 1), o[1] + 0.5 * ((child >> 1) & 1), o[2] + 0.5 * (child >> 2)},
        0.5);
  }
}

}  // namespace

void hexahedra_refined_in_half(CellMesh& m, LatticePoint o) {
  if (o[0] >= m.n / 2) return refined_cube(m, o);
  hexahedra(m, o);
  m.coarse_cubes.insert(o);
}

void hexahedra_refined_alternately(CellMesh& m, LatticePoint o) {
  if (static_cast<int>(o[0] + o[1] + o[2]) % 2 == 0) return refined_cube(m, o);
  hexahedra(m, o);
  m.coarse_cubes.insert(o);
}

void hexahedra_refined_in_an_l(CellMesh& m, LatticePoint o) {
  if (o[0] >= m.n / 2 || o[1] >= m.n / 2) return refined_cube(m, o);
  hexahedra(m, o);
  m.coarse_cubes.insert(o);
}

void constrain_hanging_values(const CellMesh& m, std::vector<double>& values) {
  // The hexahedra, largest first: a point on a larger cell's boundary takes its value from that
  // cell's corners, whose own values (hanging on a still larger cell, maybe) are final by then.
  struct Cube {
    LatticePoint lo;
    double side;
    std::int64_t first;  // its nodes start at connectivity[first]
  };
  std::vector<Cube> cubes;
  for (std::size_t c = 0; c < m.types.size(); ++c) {
    if (m.types[c] != VTK_HEXAHEDRON) continue;
    const auto first = m.offsets[c];
    const LatticePoint& lo = m.points[m.connectivity[first]];
    const LatticePoint& hi = m.points[m.connectivity[first + 6]];
    cubes.push_back({lo, hi[0] - lo[0], first});
  }
  std::stable_sort(cubes.begin(), cubes.end(),
                   [](const Cube& a, const Cube& b) { return a.side > b.side; });
  constexpr double kFinest = 0.125;  // the lattice's finest step: an eighth
  for (const Cube& cube : cubes) {
    const int steps = static_cast<int>(std::lround(cube.side / kFinest));
    double corner[8];
    for (int k = 0; k < 8; ++k) corner[k] = values[m.connectivity[cube.first + k]];
    for (int a = 0; a <= steps; ++a)
      for (int b = 0; b <= steps; ++b)
        for (int c = 0; c <= steps; ++c) {
          const bool on_boundary =
              a == 0 || b == 0 || c == 0 || a == steps || b == steps || c == steps;
          const bool is_corner =
              (a == 0 || a == steps) && (b == 0 || b == steps) && (c == 0 || c == steps);
          if (!on_boundary || is_corner) continue;
          const LatticePoint q = {cube.lo[0] + a * kFinest, cube.lo[1] + b * kFinest,
                                  cube.lo[2] + c * kFinest};
          const std::int64_t p = m.find(q);
          if (p < 0) continue;
          // Trilinear in VTK's corner order (x fastest round the bottom face, then the top).
          const double u = double(a) / steps, v = double(b) / steps, w = double(c) / steps;
          const double bottom = (1 - v) * ((1 - u) * corner[0] + u * corner[1]) +
                                v * ((1 - u) * corner[3] + u * corner[2]);
          const double top = (1 - v) * ((1 - u) * corner[4] + u * corner[5]) +
                             v * ((1 - u) * corner[7] + u * corner[6]);
          values[static_cast<std::size_t>(p)] = (1 - w) * bottom + w * top;
        }
  }
}

void hexahedra_refined_twice_along_an_edge(CellMesh& m, LatticePoint o) {
  if (o == LatticePoint{1, 1, 1}) {
    hexahedra(m, o);
    m.coarse_cubes.insert(o);
    return;
  }
  if (o != LatticePoint{2, 2, 1}) return refined_cube(m, o);
  // Seven children of half the side, and the eighth, at the corner on the coarse cube's edge
  // x = y = 2, in eight of a quarter.
  for (int child = 1; child < 8; ++child) {
    add_hexahedron(
        m, {o[0] + 0.5 * (child & 1), o[1] + 0.5 * ((child >> 1) & 1), o[2] + 0.5 * (child >> 2)},
        0.5);
  }
  for (int child = 0; child < 8; ++child) {
    add_hexahedron(
        m,
        {o[0] + 0.25 * (child & 1), o[1] + 0.25 * ((child >> 1) & 1), o[2] + 0.25 * (child >> 2)},
        0.25);
  }
}

CellMesh lattice(int n, CellMaker make) {
  CellMesh m;
  m.n = n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) make(m, {double(i), double(j), double(k)});
  return m;
}

}  // namespace tetray::testing
