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

// Eight hexahedra of half the side, VTK's corner order in each.
void refined_cube(CellMesh& m, LatticePoint o) {
  const int dx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dy[8] = {0, 0, 1, 1, 0, 0, 1, 1},
            dz[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  for (int child = 0; child < 8; ++child) {
    const LatticePoint half = {o[0] + 0.5 * (child & 1), o[1] + 0.5 * ((child >> 1) & 1),
                               o[2] + 0.5 * (child >> 2)};
    std::vector<std::int64_t> nodes;
    for (int k = 0; k < 8; ++k) {
      nodes.push_back(
          m.point({half[0] + 0.5 * dx[k], half[1] + 0.5 * dy[k], half[2] + 0.5 * dz[k]}));
    }
    m.add(VTK_HEXAHEDRON, nodes);
  }
}

bool is_coarse_cube(const CellMesh& m, LatticePoint o) {
  for (double x : o) {
    if (x < 0 || x >= m.n) return false;
  }
  return m.coarse_cubes.count(o) != 0;
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
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const LatticePoint& x = m.points[p];
    std::vector<int> halves;
    for (int k = 0; k < 3; ++k) {
      if (x[k] != std::floor(x[k])) halves.push_back(k);
    }
    if (halves.empty() || halves.size() == 3) continue;
    // The coarse cubes that may hold x on their boundary: each integer coordinate on either side.
    bool hanging = false;
    for (int corner = 0; corner < 8 && !hanging; ++corner) {
      LatticePoint o{};
      for (int k = 0; k < 3; ++k) {
        o[k] = std::floor(x[k]) - ((x[k] == std::floor(x[k]) && (corner >> k & 1)) ? 1 : 0);
      }
      hanging = is_coarse_cube(m, o);
    }
    if (!hanging) continue;
    double sum = 0;
    int count = 0;
    for (int s = 0; s < (1 << halves.size()); ++s) {
      LatticePoint q = x;
      for (std::size_t h = 0; h < halves.size(); ++h) q[halves[h]] += (s >> h & 1) ? 0.5 : -0.5;
      sum += values[m.index_of(q)];
      ++count;
    }
    values[p] = sum / count;
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
