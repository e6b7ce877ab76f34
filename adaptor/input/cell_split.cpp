#include "adaptor/input/cell_split.hpp"

#include <array>

namespace tetray {
namespace {

// A face of a linear cell: positions in the cell's node list, in cyclic order.
struct Face {
  int count;
  std::array<int, 4> at;
};

constexpr Face kHexahedronFaces[] = {{4, {0, 1, 2, 3}}, {4, {4, 5, 6, 7}}, {4, {0, 1, 5, 4}},
                                     {4, {1, 2, 6, 5}}, {4, {2, 3, 7, 6}}, {4, {3, 0, 4, 7}}};
constexpr Face kWedgeFaces[] = {
    {3, {0, 1, 2}}, {3, {3, 4, 5}}, {4, {0, 1, 4, 3}}, {4, {1, 2, 5, 4}}, {4, {2, 0, 3, 5}}};
constexpr Face kPyramidFaces[] = {
    {4, {0, 1, 2, 3}}, {3, {0, 1, 4}}, {3, {1, 2, 4}}, {3, {2, 3, 4}}, {3, {3, 0, 4}}};

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
  Splitter(std::span<const std::uint64_t> keys, SplitCells& out) : keys_(keys), out_(out) {}

  void split(CellType type, std::span<const std::int64_t> nodes, std::uint64_t cell) {
    cell_ = cell;
    switch (type) {
      case CellType::tetra:
        emit(nodes[0], nodes[1], nodes[2], nodes[3]);
        return;
      case CellType::hexahedron:
        return cone(nodes, kHexahedronFaces);
      case CellType::wedge:
        return cone(nodes, kWedgeFaces);
      case CellType::pyramid:
        return cone(nodes, kPyramidFaces);
      case CellType::quadratic_tetra:
        return quadratic_tetra(nodes);
      case CellType::lagrange_tetrahedron:
        return nodes.size() == 4 ? split(CellType::tetra, nodes, cell) : quadratic_tetra(nodes);
      case CellType::lagrange_hexahedron:
        return nodes.size() == 8 ? cone(nodes, kHexahedronFaces) : quadratic_hexahedron(nodes);
    }
  }

 private:
  bool smaller(std::int64_t a, std::int64_t b) const {
    return keys_[a] < keys_[b] || (keys_[a] == keys_[b] && a < b);
  }

  void emit(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {
    out_.tets.insert(out_.tets.end(), {a, b, c, d});
    out_.tet_cell.push_back(cell_);
  }

  // Tets from the cell's smallest node to the triangles of every face that does not hold it; a
  // quadrilateral face is cut by the diagonal through its own smallest node. The faces that hold
  // the smallest node come out cut through it: the same rule.
  template <std::size_t N>
  void cone(std::span<const std::int64_t> nodes, const Face (&faces)[N]) {
    std::int64_t apex = nodes[0];
    for (std::int64_t node : nodes.first(corner_count(faces))) {
      if (smaller(node, apex)) apex = node;
    }
    for (const Face& face : faces) {
      std::array<std::int64_t, 4> f{};
      bool holds_apex = false;
      for (int k = 0; k < face.count; ++k) {
        f[k] = nodes[face.at[k]];
        holds_apex = holds_apex || f[k] == apex;
      }
      if (holds_apex) continue;
      if (face.count == 3) {
        emit(apex, f[0], f[1], f[2]);
        continue;
      }
      int s = 0;
      for (int k = 1; k < 4; ++k) {
        if (smaller(f[k], f[s])) s = k;
      }
      const auto at = [&](int k) { return f[(s + k) % 4]; };
      emit(apex, at(0), at(1), at(2));
      emit(apex, at(0), at(2), at(3));
    }
  }

  template <std::size_t N>
  static std::size_t corner_count(const Face (&faces)[N]) {
    int highest = 0;
    for (const Face& face : faces) {
      for (int k = 0; k < face.count; ++k) highest = std::max(highest, face.at[k]);
    }
    return static_cast<std::size_t>(highest + 1);
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
        }
  }

  std::span<const std::uint64_t> keys_;
  SplitCells& out_;
  std::uint64_t cell_ = 0;
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

}  // namespace

SplitCells split_cells(std::span<const std::uint8_t> types, std::span<const std::int64_t> offsets,
                       std::span<const std::int64_t> connectivity,
                       std::span<const std::uint64_t> point_keys) {
  SplitCells out;
  out.error = offsets_problem(offsets, types.size(), connectivity.size());
  if (!out.error.empty()) return out;
  Splitter splitter(point_keys, out);
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
