// Splitting the cells solvers write into tets: every split fills its cell exactly (the tets'
// volumes add up to the cell's, none is flat), neighbouring cells split their shared faces alike
// (every triangle inside the mesh is a face of exactly two tets, under any order of the points),
// a subset of the cells splits as in the whole mesh (as on another rank), and what tetray cannot
// split is an error naming the cell. The 27-node hexahedron's node order is checked against VTK.
#include <gtest/gtest.h>
#include <vtkLagrangeHexahedron.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "cell_split.hpp"

namespace tetray {
namespace {

using Point = std::array<double, 3>;

// A mesh of cells of one kind on the lattice [0, n]^3 (integer coordinates where a cell has
// corners, halves at quadratic nodes and cell centres).
struct CellMesh {
  std::vector<Point> points;
  std::vector<std::uint8_t> types;
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> connectivity;
  int n = 0;

  std::int64_t point(Point p) {
    const auto found = index.find(p);
    if (found != index.end()) return found->second;
    points.push_back(p);
    return index[p] = static_cast<std::int64_t>(points.size() - 1);
  }
  void add(CellType type, const std::vector<std::int64_t>& nodes) {
    types.push_back(static_cast<std::uint8_t>(type));
    connectivity.insert(connectivity.end(), nodes.begin(), nodes.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }

 private:
  std::map<Point, std::int64_t> index;
};

using CellMaker = void (*)(CellMesh&, Point);  // adds the cells of the unit cube at a corner

std::array<std::int64_t, 8> cube_corners(CellMesh& m, Point o) {
  std::array<std::int64_t, 8> c{};
  const int dx[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dy[8] = {0, 0, 1, 1, 0, 0, 1, 1},
            dz[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  for (int k = 0; k < 8; ++k) c[k] = m.point({o[0] + dx[k], o[1] + dy[k], o[2] + dz[k]});
  return c;
}

void hexahedra(CellMesh& m, Point o) {
  const auto c = cube_corners(m, o);
  m.add(CellType::hexahedron, {c.begin(), c.end()});
}

void wedges(CellMesh& m, Point o) {
  const auto c = cube_corners(m, o);
  m.add(CellType::wedge, {c[0], c[1], c[2], c[4], c[5], c[6]});
  m.add(CellType::wedge, {c[0], c[2], c[3], c[4], c[6], c[7]});
}

// Six pyramids from the cube's centre to its faces.
void pyramids(CellMesh& m, Point o) {
  const auto c = cube_corners(m, o);
  const std::int64_t centre = m.point({o[0] + 0.5, o[1] + 0.5, o[2] + 0.5});
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& f : faces) {
    m.add(CellType::pyramid, {c[f[0]], c[f[1]], c[f[2]], c[f[3]], centre});
  }
}

Point mid(const CellMesh& m, std::int64_t a, std::int64_t b) {
  const Point& p = m.points[a];
  const Point& q = m.points[b];
  return {0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])};
}

// Six Kuhn tets of 10 nodes each (VTK order: corners, then edges 01, 12, 02, 03, 13, 23).
void quadratic_tets(CellMesh& m, Point o) {
  const auto c = cube_corners(m, o);
  const int kuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                          {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  for (int t = 0; t < 6; ++t) {
    std::vector<std::int64_t> nodes;
    for (int v : kuhn[t]) nodes.push_back(c[v]);
    for (const auto& e : edges) nodes.push_back(m.point(mid(m, nodes[e[0]], nodes[e[1]])));
    m.add(t % 2 ? CellType::quadratic_tetra : CellType::lagrange_tetrahedron, nodes);
  }
}

// One 27-node Lagrange hexahedron, its nodes ordered by VTK's own vtkLagrangeHexahedron.
void quadratic_hexahedra(CellMesh& m, Point o) {
  vtkNew<vtkLagrangeHexahedron> cell;
  cell->SetOrder(2, 2, 2);
  std::vector<std::int64_t> nodes(27);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        nodes[cell->PointIndexFromIJK(i, j, k)] =
            m.point({o[0] + 0.5 * i, o[1] + 0.5 * j, o[2] + 0.5 * k});
      }
  m.add(CellType::lagrange_hexahedron, nodes);
}

CellMesh lattice(int n, CellMaker make) {
  CellMesh m;
  m.n = n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) make(m, {double(i), double(j), double(k)});
  return m;
}

std::vector<std::uint64_t> shuffled_keys(std::size_t count, unsigned seed) {
  std::vector<std::uint64_t> keys(count);
  std::iota(keys.begin(), keys.end(), 0);
  std::shuffle(keys.begin(), keys.end(), std::mt19937(seed));
  return keys;
}

double volume(const CellMesh& m, const std::int64_t* t) {
  const Point &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]], &d = m.points[t[3]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6;
}

bool on_boundary(const CellMesh& m, const std::array<std::int64_t, 3>& face) {
  for (int a = 0; a < 3; ++a) {
    for (double side : {0.0, double(m.n)}) {
      if (std::all_of(face.begin(), face.end(),
                      [&](std::int64_t p) { return m.points[p][a] == side; })) {
        return true;
      }
    }
  }
  return false;
}

// Splits `m` under `keys` and checks the tets fill it without gaps, overlaps or cracks.
void expect_conforming_split(const CellMesh& m, const std::vector<std::uint64_t>& keys,
                             const char* label) {
  const SplitCells split = split_cells(m.types, m.offsets, m.connectivity, keys);
  ASSERT_EQ(split.error, "") << label;
  ASSERT_EQ(split.tet_cell.size() * 4, split.tets.size()) << label;
  double total = 0;
  std::map<std::array<std::int64_t, 3>, int> faces;
  for (std::size_t t = 0; t < split.tet_cell.size(); ++t) {
    const std::int64_t* tet = &split.tets[4 * t];
    const double v = std::abs(volume(m, tet));
    EXPECT_GT(v, 1e-9) << label << ": tet " << t << " of cell " << split.tet_cell[t] << " is flat";
    total += v;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<std::int64_t, 3> face{};
      for (int k = 0, f = 0; k < 4; ++k) {
        if (k != skip) face[f++] = tet[k];
      }
      std::sort(face.begin(), face.end());
      ++faces[face];
    }
  }
  EXPECT_NEAR(total, double(m.n) * m.n * m.n, 1e-9) << label << ": the tets do not fill the mesh";
  for (const auto& [face, count] : faces) {
    const int expected = on_boundary(m, face) ? 1 : 2;
    EXPECT_EQ(count, expected) << label << ": triangle " << face[0] << " " << face[1] << " "
                               << face[2] << (expected == 1 ? " on the boundary" : " inside");
  }
}

struct Kind {
  const char* name;
  CellMaker make;
};
const Kind kKinds[] = {{"hexahedra", hexahedra},
                       {"wedges", wedges},
                       {"pyramids", pyramids},
                       {"quadratic tets", quadratic_tets},
                       {"quadratic hexahedra", quadratic_hexahedra}};

TEST(CellSplit, FillsTheMeshAndConformsUnderAnyPointOrder) {
  for (const Kind& kind : kKinds) {
    const CellMesh m = lattice(3, kind.make);
    for (unsigned seed = 1; seed <= 8; ++seed) {
      expect_conforming_split(m, shuffled_keys(m.points.size(), seed), kind.name);
    }
  }
}

// A rank holding some of the cells splits each as the whole mesh does.
TEST(CellSplit, ASubsetOfTheCellsSplitsAsInTheWholeMesh) {
  for (const Kind& kind : kKinds) {
    const CellMesh m = lattice(3, kind.make);
    const std::vector<std::uint64_t> keys = shuffled_keys(m.points.size(), 5);
    const SplitCells whole = split_cells(m.types, m.offsets, m.connectivity, keys);
    const std::size_t first = m.types.size() / 3, last = 2 * m.types.size() / 3;
    std::vector<std::int64_t> offsets;
    for (std::size_t c = first; c <= last; ++c) offsets.push_back(m.offsets[c] - m.offsets[first]);
    const SplitCells part =
        split_cells(std::span(m.types).subspan(first, last - first), offsets,
                    std::span(m.connectivity)
                        .subspan(static_cast<std::size_t>(m.offsets[first]),
                                 static_cast<std::size_t>(m.offsets[last] - m.offsets[first])),
                    keys);
    ASSERT_EQ(part.error, "");
    const auto begin = std::find(whole.tet_cell.begin(), whole.tet_cell.end(), first);
    const std::size_t offset = static_cast<std::size_t>(begin - whole.tet_cell.begin());
    ASSERT_LE(4 * offset + part.tets.size(), whole.tets.size());
    EXPECT_TRUE(std::equal(part.tets.begin(), part.tets.end(), whole.tets.begin() + 4 * offset))
        << kind.name;
  }
}

TEST(CellSplit, WhatItCannotSplitIsAnErrorNamingTheCell) {
  const std::vector<std::uint64_t> keys(30, 0);
  const std::vector<std::int64_t> nodes(20, 0);
  struct Case {
    std::uint8_t type;
    std::size_t nodes;
    const char* message;
  };
  const Case cases[] = {{42, 8, "cell 1 (VTK cell type 42) is not a cell tetray renders"},
                        {71, 20, "Lagrange tetrahedra of order 1 (4 nodes) and 2 (10 nodes)"},
                        {72, 20, "Lagrange hexahedra of order 1 (8 nodes) and 2 (27 nodes)"},
                        {12, 7, "cell 1 (VTK cell type 12) has 7 nodes, not 8"}};
  for (const Case& c : cases) {
    const std::vector<std::uint8_t> types = {10, c.type};
    const std::vector<std::int64_t> offsets = {0, 4, static_cast<std::int64_t>(4 + c.nodes)};
    const SplitCells split = split_cells(types, offsets, std::span(nodes).first(4 + c.nodes), keys);
    EXPECT_NE(split.error.find(c.message), std::string::npos) << split.error;
  }
  const std::vector<std::uint8_t> tet = {10};
  const std::vector<std::int64_t> out_of_range = {0, 1, 2, 30}, offsets = {0, 4};
  EXPECT_NE(split_cells(tet, offsets, out_of_range, keys).error.find("names point 30 outside"),
            std::string::npos);
  const std::vector<std::int64_t> short_offsets = {0, 9};
  EXPECT_NE(split_cells(tet, short_offsets, out_of_range, keys).error.find("run outside"),
            std::string::npos);
}

}  // namespace
}  // namespace tetray
