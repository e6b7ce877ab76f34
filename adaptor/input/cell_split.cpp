#include "adaptor/input/cell_split.hpp"

#include <algorithm>
#include <array>

#include "adaptor/input/cell_faces.hpp"
#include "adaptor/input/hanging_nodes.hpp"
#include "render/core/hash.hpp"

namespace tetray {
namespace {

// The 10-node tet (VTK order: corners, then the midpoints of edges 01, 12, 02, 03, 13, 23) as
// its four corner tets and the inner octahedron cut along the diagonal from node 4 to node 9.
// Each face of the cell is cut into the same four triangles from either side, so neighbouring
// cells conform whatever the point keys.
constexpr std::array<std::array<int, 4>, 8> kQuadraticTetraSplit = {{{0, 4, 6, 7},
                                                                     {4, 1, 5, 8},
                                                                     {6, 5, 2, 9},
                                                                     {7, 8, 9, 3},
                                                                     {4, 9, 5, 6},
                                                                     {4, 9, 6, 7},
                                                                     {4, 9, 7, 8},
                                                                     {4, 9, 8, 5}}};

// The node of the 27-node Lagrange hexahedron at grid position (i, j, k) in {0, 1, 2}^3 (VTK's
// order: corners, edge midpoints, face centres x-, x+, y-, y+, z-, z+, then the body centre).
constexpr std::array<std::array<std::array<int, 3>, 3>, 3> kLagrangeHexahedronNode = {{
    {{{0, 16, 4}, {11, 20, 15}, {3, 19, 7}}},     // i = 0: [j][k]
    {{{8, 22, 12}, {24, 26, 25}, {10, 23, 14}}},  // i = 1
    {{{1, 17, 5}, {9, 21, 13}, {2, 18, 6}}},      // i = 2
}};

int node_count(CellType type) {
  switch (type) {
    case CellType::tetra:
      return 4;
    case CellType::hexahedron:
      return 8;
    case CellType::wedge:
      return 6;
    case CellType::pyramid:
      return 5;
    case CellType::quadratic_tetra:
      return 10;
    case CellType::lagrange_tetrahedron:
    case CellType::lagrange_hexahedron:
      return 0;  // by order: checked apart
  }
  return -1;
}

bool known_type(std::uint8_t type) {
  switch (static_cast<CellType>(type)) {
    case CellType::tetra:
    case CellType::hexahedron:
    case CellType::wedge:
    case CellType::pyramid:
    case CellType::quadratic_tetra:
    case CellType::lagrange_tetrahedron:
    case CellType::lagrange_hexahedron:
      return true;
  }
  return false;
}

class Splitter {
 public:
  Splitter(std::span<const std::uint64_t> keys, const HangingNodes& hanging, SplitCells& out)
      : keys_(keys), hanging_(hanging), out_(out) {}

  void split(CellType type, std::span<const std::int64_t> nodes, std::uint64_t cell) {
    cell_ = cell;
    switch (type) {
      case CellType::quadratic_tetra:
        return quadratic_tetra(nodes);
      case CellType::lagrange_tetrahedron:
        if (nodes.size() == 10) return quadratic_tetra(nodes);
        break;
      case CellType::lagrange_hexahedron:
        if (nodes.size() == 27) return quadratic_hexahedron(nodes);
        break;
      default:
        break;
    }
    linear_cell(nodes, linear_cell_faces(type, nodes.size()));
  }

 private:
  // The order of the points: a hanging face centre before all others (so the finer cells cut
  // their faces through it, as the coarse cell's bisection does), then by key, then by index.
  bool smaller(std::int64_t a, std::int64_t b) const {
    const bool centre_a = hanging_.is_centre(a), centre_b = hanging_.is_centre(b);
    if (centre_a != centre_b) return centre_a;
    return keys_[a] < keys_[b] || (keys_[a] == keys_[b] && a < b);
  }

  void emit(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {
    out_.tets.insert(out_.tets.end(), {a, b, c, d});
    out_.tet_cell.push_back(cell_);
  }

  void linear_cell(std::span<const std::int64_t> nodes, std::span<const CellFace> faces) {
    if (faces.size() == 4) {  // a tet
      cell_tets_.assign(1, {nodes[0], nodes[1], nodes[2], nodes[3]});
    } else {
      cone(nodes, faces);
    }
    if (!hanging_.empty() && touches_hanging_edge(nodes)) bisect_at_hanging_nodes(nodes, faces);
    for (const auto& t : cell_tets_) emit(t[0], t[1], t[2], t[3]);
  }

  // The quadrilateral face's corners from its smallest, cyclic: the face is cut from corner 0 to
  // corner 2.
  std::array<std::int64_t, 4> from_smallest(std::span<const std::int64_t> nodes,
                                            const CellFace& face) const {
    int s = 0;
    for (int k = 1; k < 4; ++k) {
      if (smaller(nodes[face.at[k]], nodes[face.at[s]])) s = k;
    }
    std::array<std::int64_t, 4> f{};
    for (int k = 0; k < 4; ++k) f[k] = nodes[face.at[(s + k) % 4]];
    return f;
  }

  // Tets from the cell's smallest node to the triangles of every face that does not hold it; a
  // quadrilateral face is cut by the diagonal through its own smallest node. The faces that hold
  // the smallest node come out cut through it: the same rule.
  void cone(std::span<const std::int64_t> nodes, std::span<const CellFace> faces) {
    cell_tets_.clear();
    std::int64_t apex = nodes[0];
    for (const CellFace& face : faces) {
      for (int k = 0; k < face.count; ++k) {
        if (smaller(nodes[face.at[k]], apex)) apex = nodes[face.at[k]];
      }
    }
    for (const CellFace& face : faces) {
      const auto holds_apex = [&] {
        for (int k = 0; k < face.count; ++k) {
          if (nodes[face.at[k]] == apex) return true;
        }
        return false;
      };
      if (holds_apex()) continue;
      if (face.count == 3) {
        cell_tets_.push_back({apex, nodes[face.at[0]], nodes[face.at[1]], nodes[face.at[2]]});
        continue;
      }
      const std::array<std::int64_t, 4> f = from_smallest(nodes, face);
      cell_tets_.push_back({apex, f[0], f[1], f[2]});
      cell_tets_.push_back({apex, f[0], f[2], f[3]});
    }
  }

  bool touches_hanging_edge(std::span<const std::int64_t> nodes) const {
    return std::any_of(nodes.begin(), nodes.end(),
                       [&](std::int64_t p) { return hanging_.ends_hanging_edge(p); });
  }

  // Bisects the cell's tets at the hanging nodes on its boundary (hanging_nodes.hpp): first at
  // each face centre, along the face's diagonal (the face then comes out as four triangles round
  // the centre), then at each edge midpoint, in the points' order, so that two cells sharing a face
  // cut it into the same triangles as each other and as the finer cells beyond it.
  void bisect_at_hanging_nodes(std::span<const std::int64_t> nodes,
                               std::span<const CellFace> faces) {
    for (const CellFace& face : faces) {
      if (face.count != 4 || !hanging_.ends_hanging_edge(nodes[face.at[0]])) continue;
      const std::array<std::int64_t, 4> f = from_smallest(nodes, face);
      const std::int64_t centre = hanging_.centre(f[0], f[1], f[2], f[3]);
      if (centre >= 0) bisect(f[0], f[2], centre);
    }
    midpoints_.clear();
    for (const CellEdge& edge : edges_of(faces)) add_midpoint(nodes[edge[0]], nodes[edge[1]]);
    // Round by round: the edges' midpoints, then those of the halves (a finer cell two levels
    // down across an edge hangs a node at a quarter of it), each round in the points' order.
    for (int round = 0; round < kMostRounds && !midpoints_.empty(); ++round) {
      std::sort(midpoints_.begin(), midpoints_.end(),
                [&](const auto& x, const auto& y) { return smaller(x[0], y[0]); });
      std::swap(midpoints_, round_);
      midpoints_.clear();
      for (const auto& [mid, a, b] : round_) {
        bisect(a, b, mid);
        add_midpoint(a, mid);
        add_midpoint(mid, b);
      }
    }
  }

  // Adds the hanging midpoint of edge (a, b), if it has one, to this round's list.
  void add_midpoint(std::int64_t a, std::int64_t b) {
    if (!hanging_.ends_hanging_edge(a) || !hanging_.ends_hanging_edge(b)) return;
    const std::int64_t mid = hanging_.midpoint(a, b);
    if (mid >= 0) midpoints_.push_back({mid, a, b});
  }

  // Replaces every tet of the cell that has the edge (a, b) by its two halves at `mid`.
  void bisect(std::int64_t a, std::int64_t b, std::int64_t mid) {
    const std::size_t count = cell_tets_.size();
    for (std::size_t t = 0; t < count; ++t) {
      std::array<std::int64_t, 4>& tet = cell_tets_[t];
      if (std::find(tet.begin(), tet.end(), mid) != tet.end()) continue;  // a collapsed cell's
      const auto at_a = std::find(tet.begin(), tet.end(), a);
      const auto at_b = std::find(tet.begin(), tet.end(), b);
      if (at_a == tet.end() || at_b == tet.end()) continue;
      std::array<std::int64_t, 4> half = tet;
      half[static_cast<std::size_t>(at_b - tet.begin())] = mid;
      *at_a = mid;
      cell_tets_.push_back(half);
    }
  }

  void quadratic_tetra(std::span<const std::int64_t> nodes) {
    for (const auto& t : kQuadraticTetraSplit)
      emit(nodes[t[0]], nodes[t[1]], nodes[t[2]], nodes[t[3]]);
  }

  // Eight linear hexahedra between the nodes, each split as a hexahedron.
  void quadratic_hexahedron(std::span<const std::int64_t> nodes) {
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int c = 0; c < 2; ++c) {
          const auto node = [&](int i, int j, int k) {
            return nodes[kLagrangeHexahedronNode[a + i][b + j][c + k]];
          };
          const std::array<std::int64_t, 8> hexahedron = {
              node(0, 0, 0), node(1, 0, 0), node(1, 1, 0), node(0, 1, 0),
              node(0, 0, 1), node(1, 0, 1), node(1, 1, 1), node(0, 1, 1)};
          cone(hexahedron, kHexahedronFaces);
          for (const auto& t : cell_tets_) emit(t[0], t[1], t[2], t[3]);
        }
  }

  std::span<const std::uint64_t> keys_;
  const HangingNodes& hanging_;
  SplitCells& out_;
  std::uint64_t cell_ = 0;
  std::vector<std::array<std::int64_t, 4>> cell_tets_;  // the tets of the cell being split
  std::vector<std::array<std::int64_t, 3>> midpoints_;  // (midpoint, a, b) of its edges
  std::vector<std::array<std::int64_t, 3>> round_;      // the round being bisected
  // Levels of refinement across an edge that a cell's bisection follows (a quarter, an eighth..).
  static constexpr int kMostRounds = 8;
};

std::string cell_text(std::size_t cell, std::uint8_t type) {
  return "cell " + std::to_string(cell) + " (VTK cell type " + std::to_string(type) + ")";
}

// Empty when cell c's type and node count are ones tetray splits and its nodes name points.
std::string cell_problem(std::size_t c, std::uint8_t type, std::span<const std::int64_t> nodes,
                         std::size_t point_count) {
  if (!known_type(type)) {
    return cell_text(c, type) +
           " is not a cell tetray renders: it takes VTK types 10 (tetra), 12 (hexahedron), 13 "
           "(wedge), 14 (pyramid), 24 (quadratic tetra), 71 (Lagrange tetrahedron of order 1 or "
           "2) and 72 (Lagrange hexahedron of order 1 or 2)";
  }
  const auto cell_type = static_cast<CellType>(type);
  const std::size_t n = nodes.size();
  const int expected = node_count(cell_type);
  if (cell_type == CellType::lagrange_tetrahedron && n != 4 && n != 10) {
    return cell_text(c, type) + " has " + std::to_string(n) +
           " nodes: tetray renders Lagrange tetrahedra of order 1 (4 nodes) and 2 (10 nodes)";
  }
  if (cell_type == CellType::lagrange_hexahedron && n != 8 && n != 27) {
    return cell_text(c, type) + " has " + std::to_string(n) +
           " nodes: tetray renders Lagrange hexahedra of order 1 (8 nodes) and 2 (27 nodes)";
  }
  if (expected > 0 && n != static_cast<std::size_t>(expected)) {
    return cell_text(c, type) + " has " + std::to_string(n) + " nodes, not " +
           std::to_string(expected);
  }
  for (std::int64_t node : nodes) {
    if (node < 0 || static_cast<std::uint64_t>(node) >= point_count) {
      return cell_text(c, type) + " names point " + std::to_string(node) + " outside [0, " +
             std::to_string(point_count) + ")";
    }
  }
  return {};
}

std::string offsets_problem(std::span<const std::int64_t> offsets, std::size_t cells,
                            std::size_t connectivity) {
  // VTK keeps no offsets at all for a grid without cells (a rank or a .pvtu piece with none):
  // that grid is empty, not broken.
  if (cells == 0 && offsets.empty()) return {};
  if (offsets.size() != cells + 1) {
    return "the cell offsets hold " + std::to_string(offsets.size()) + " entries for " +
           std::to_string(cells) + " cells (one more than the cells are needed)";
  }
  if (offsets[0] != 0) return "the cell offsets do not start at 0";
  for (std::size_t c = 0; c < cells; ++c) {
    if (offsets[c + 1] < offsets[c] || static_cast<std::uint64_t>(offsets[c + 1]) > connectivity) {
      return "the cell offsets of cell " + std::to_string(c) + " run outside the " +
             std::to_string(connectivity) + " connectivity entries";
    }
  }
  return {};
}

bool has_quadrilateral_faces(std::span<const std::uint8_t> types) {
  return std::any_of(types.begin(), types.end(), [](std::uint8_t t) {
    const auto type = static_cast<CellType>(t);
    return type == CellType::hexahedron || type == CellType::wedge || type == CellType::pyramid ||
           type == CellType::lagrange_hexahedron;
  });
}

}  // namespace

std::vector<std::uint64_t> position_keys(std::span<const double> xyz) {
  std::vector<std::uint64_t> keys(xyz.size() / 3);
  for (std::size_t p = 0; p < keys.size(); ++p) {
    keys[p] = render::position_hash(xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]);
  }
  return keys;
}

SplitCells split_cells(std::span<const std::uint8_t> types, std::span<const std::int64_t> offsets,
                       std::span<const std::int64_t> connectivity,
                       std::span<const std::uint64_t> point_keys, std::span<const double> xyz) {
  SplitCells out;
  out.error = offsets_problem(offsets, types.size(), connectivity.size());
  if (!out.error.empty()) return out;
  // Octree refinement leaves hanging nodes on hexahedra (and the cells mixed with them); meshes of
  // tets alone are refined conformingly and are not searched.
  const bool searched = xyz.size() == 3 * point_keys.size() && has_quadrilateral_faces(types);
  const HangingNodes hanging =
      searched ? HangingNodes::find(types, offsets, connectivity, xyz) : HangingNodes();
  out.hanging_midpoints = hanging.midpoint_count();
  out.hanging_centres = hanging.centre_count();
  Splitter splitter(point_keys, hanging, out);
  for (std::size_t c = 0; c < types.size(); ++c) {
    const auto nodes = connectivity.subspan(static_cast<std::size_t>(offsets[c]),
                                            static_cast<std::size_t>(offsets[c + 1] - offsets[c]));
    out.error = cell_problem(c, types[c], nodes, point_keys.size());
    if (!out.error.empty()) return out;
    splitter.split(static_cast<CellType>(types[c]), nodes, c);
  }
  return out;
}

}  // namespace tetray
