// Splitting the cells solvers write into tets: every split fills its cell exactly (the tets'
// volumes add up to the cell's, none is flat), neighbouring cells split their shared faces alike
// (every triangle inside the mesh is a face of exactly two tets, under any order of the points),
// a subset of the cells splits as in the whole mesh (as on another rank), and what tetray cannot
// split is an error naming the cell. The 27-node hexahedron's node order is checked against VTK.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "adaptor/input/cell_split.hpp"
#include "support/cell_meshes.hpp"

namespace tetray {
namespace {

using testing::CellMesh;
using testing::kCellKinds;
using testing::lattice;
using Point = testing::LatticePoint;

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
// xyz places the points for the hanging-node search (the lattice's own positions by default);
// volumes and the boundary are checked on the lattice.
void expect_conforming_split(const CellMesh& m, const std::vector<std::uint64_t>& keys,
                             const char* label, const std::vector<double>& xyz = {}) {
  const SplitCells split =
      split_cells(m.types, m.offsets, m.connectivity, keys, xyz.empty() ? m.xyz(0, m.n) : xyz);
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

TEST(CellSplit, FillsTheMeshAndConformsUnderAnyPointOrder) {
  for (const testing::CellKind& kind : kCellKinds) {
    const CellMesh m = lattice(3, kind.make);
    for (unsigned seed = 1; seed <= 8; ++seed) {
      expect_conforming_split(m, shuffled_keys(m.points.size(), seed), kind.name);
    }
  }
}

// Where coarse cubes meet refined ones, the coarse cells' tets are bisected at the hanging nodes:
// every triangle inside the mesh is still a face of exactly two tets (a coarse face against four
// fine ones would leave eight triangles and two of another shape each a face of one tet), under
// any order of the points.
TEST(CellSplit, ConformsWhereCoarseCellsMeetRefinedOnesUnderAnyPointOrder) {
  for (const testing::CellKind& kind : testing::kHangingKinds) {
    const CellMesh m = lattice(4, kind.make);
    for (unsigned seed = 1; seed <= 8; ++seed) {
      expect_conforming_split(m, shuffled_keys(m.points.size(), seed), kind.name);
    }
  }
}

// On [0, 4]^3 refined where x >= 2, the interface x = 2 holds 4 x 4 coarse faces: 16 hanging
// centres, and 2 x 5 x 4 = 40 coarse edges, each with a hanging midpoint. Nothing hangs in a mesh
// refined everywhere, or in one of tets (whose faces' edges have no third point at their middle).
TEST(CellSplit, FindsEachHangingNodeAndNoOther) {
  const CellMesh half = lattice(4, testing::hexahedra_refined_in_half);
  SplitCells split = split_cells(half.types, half.offsets, half.connectivity,
                                 shuffled_keys(half.points.size(), 3), half.xyz());
  EXPECT_EQ(split.hanging_centres, 16u);
  EXPECT_EQ(split.hanging_midpoints, 40u);
  for (const testing::CellKind& kind : kCellKinds) {
    const CellMesh m = lattice(3, kind.make);
    split =
        split_cells(m.types, m.offsets, m.connectivity, shuffled_keys(m.points.size(), 3), m.xyz());
    EXPECT_EQ(split.hanging_midpoints + split.hanging_centres, 0u) << kind.name;
  }
}

// Each rank numbers its points its own way: the tets of every cell, as sets of points, are the
// same under any numbering (keys follow their points). The order of a cell's bisections must
// follow the keys, not the indices, or two ranks cut a face with two hanging edges apart.
TEST(CellSplit, HangingNodesSplitAlikeUnderAnyNumberingOfThePoints) {
  for (const testing::CellKind& kind : testing::kHangingKinds) {
    const CellMesh m = lattice(4, kind.make);
    const std::vector<std::uint64_t> keys = shuffled_keys(m.points.size(), 11);
    const std::vector<double> xyz = m.xyz();
    // The tets of each cell as sorted point quadruples, in the original numbering.
    const auto tets_by_cell = [&](const SplitCells& split,
                                  const std::vector<std::int64_t>& original) {
      std::vector<std::vector<std::array<std::int64_t, 4>>> cells(m.types.size());
      for (std::size_t t = 0; t < split.tet_cell.size(); ++t) {
        std::array<std::int64_t, 4> tet{};
        for (int k = 0; k < 4; ++k) tet[k] = original[split.tets[4 * t + k]];
        std::sort(tet.begin(), tet.end());
        cells[split.tet_cell[t]].push_back(tet);
      }
      for (auto& c : cells) std::sort(c.begin(), c.end());
      return cells;
    };
    std::vector<std::int64_t> identity(m.points.size());
    std::iota(identity.begin(), identity.end(), 0);
    const auto reference =
        tets_by_cell(split_cells(m.types, m.offsets, m.connectivity, keys, xyz), identity);
    for (unsigned seed = 1; seed <= 8; ++seed) {
      std::vector<std::int64_t> original = identity;  // original[new index] = old index
      std::shuffle(original.begin(), original.end(), std::mt19937(seed));
      std::vector<std::int64_t> renumbered(m.points.size());
      std::vector<std::uint64_t> new_keys(m.points.size());
      std::vector<double> new_xyz(xyz.size());
      for (std::size_t p = 0; p < original.size(); ++p) {
        const auto old = static_cast<std::size_t>(original[p]);
        renumbered[old] = static_cast<std::int64_t>(p);
        new_keys[p] = keys[old];
        std::copy_n(&xyz[3 * old], 3, &new_xyz[3 * p]);
      }
      std::vector<std::int64_t> connectivity(m.connectivity.size());
      for (std::size_t k = 0; k < connectivity.size(); ++k) {
        connectivity[k] = renumbered[static_cast<std::size_t>(m.connectivity[k])];
      }
      const SplitCells split = split_cells(m.types, m.offsets, connectivity, new_keys, new_xyz);
      EXPECT_EQ(tets_by_cell(split, original), reference) << kind.name << ", seed " << seed;
    }
  }
}

// Solvers place new vertices on curved boundaries and manifolds, off the straight edge, and float
// coordinates far from the origin round by more than a small cell's 1e-4: the hanging nodes are
// found all the same, and the split conforms.
TEST(CellSplit, FindsHangingNodesOffTheChordAndFarFromTheOrigin) {
  const CellMesh m = lattice(4, testing::hexahedra_refined_in_half);
  std::vector<double> curved = m.xyz(0, m.n), far = curved;
  for (std::size_t p = 0; p < curved.size(); p += 3) {
    curved[p] += 0.05 * std::sin(3 * curved[p + 1]);  // 15% of a coarse edge at most
    for (int k = 0; k < 3; ++k) far[p + k] = static_cast<float>(far[p + k] / 4 + 1000);
  }
  for (const auto& [xyz, label] : {std::pair{curved, "curved"}, std::pair{far, "far, in float"}}) {
    const std::vector<std::uint64_t> keys = shuffled_keys(m.points.size(), 7);
    const SplitCells split = split_cells(m.types, m.offsets, m.connectivity, keys, xyz);
    EXPECT_EQ(split.hanging_centres, 16u) << label;
    EXPECT_EQ(split.hanging_midpoints, 40u) << label;
    expect_conforming_split(m, keys, label, xyz);
  }
}

// A wedge whose top triangle has collapsed to one position (three distinct points there): its
// edges of no length have no middle, and it splits into its three tets, nothing bisected.
TEST(CellSplit, ACollapsedCellHasNoHangingNodes) {
  const std::vector<std::uint8_t> types = {13};
  const std::vector<std::int64_t> offsets = {0, 6}, nodes = {0, 1, 2, 3, 4, 5};
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const SplitCells split = split_cells(types, offsets, nodes, shuffled_keys(6, 2), xyz);
  EXPECT_EQ(split.hanging_midpoints, 0u);
  EXPECT_EQ(split.tet_cell.size(), 3u);
}

// A rank holding some of the cells splits each as the whole mesh does.
TEST(CellSplit, ASubsetOfTheCellsSplitsAsInTheWholeMesh) {
  for (const testing::CellKind& kind : kCellKinds) {
    const CellMesh m = lattice(3, kind.make);
    const std::vector<std::uint64_t> keys = shuffled_keys(m.points.size(), 5);
    const std::vector<double> xyz = m.xyz();
    const SplitCells whole = split_cells(m.types, m.offsets, m.connectivity, keys, xyz);
    const std::size_t first = m.types.size() / 3, last = 2 * m.types.size() / 3;
    std::vector<std::int64_t> offsets;
    for (std::size_t c = first; c <= last; ++c) offsets.push_back(m.offsets[c] - m.offsets[first]);
    const SplitCells part =
        split_cells(std::span(m.types).subspan(first, last - first), offsets,
                    std::span(m.connectivity)
                        .subspan(static_cast<std::size_t>(m.offsets[first]),
                                 static_cast<std::size_t>(m.offsets[last] - m.offsets[first])),
                    keys, xyz);
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
    const SplitCells split =
        split_cells(types, offsets, std::span(nodes).first(4 + c.nodes), keys, {});
    EXPECT_NE(split.error.find(c.message), std::string::npos) << split.error;
  }
  const std::vector<std::uint8_t> tet = {10};
  const std::vector<std::int64_t> out_of_range = {0, 1, 2, 30}, offsets = {0, 4};
  EXPECT_NE(split_cells(tet, offsets, out_of_range, keys, {}).error.find("names point 30 outside"),
            std::string::npos);
  const std::vector<std::int64_t> short_offsets = {0, 9};
  EXPECT_NE(split_cells(tet, short_offsets, out_of_range, keys, {}).error.find("run outside"),
            std::string::npos);
}

}  // namespace
}  // namespace tetray
