// The faces of the linear cells tetray splits, as positions in the cell's node list (VTK's node
// order), each face's nodes in cyclic order: the split cones a cell into these faces' triangles,
// and the hanging nodes are found along their edges.
#pragma once

#include <array>
#include <span>

#include "adaptor/input/cell_split.hpp"

namespace tetray {

struct CellFace {
  int count;  // 3 or 4 nodes
  std::array<int, 4> at;
};

inline constexpr CellFace kTetraFaces[] = {
    {3, {0, 1, 2}}, {3, {0, 1, 3}}, {3, {1, 2, 3}}, {3, {2, 0, 3}}};
inline constexpr CellFace kHexahedronFaces[] = {{4, {0, 1, 2, 3}}, {4, {4, 5, 6, 7}},
                                                {4, {0, 1, 5, 4}}, {4, {1, 2, 6, 5}},
                                                {4, {2, 3, 7, 6}}, {4, {3, 0, 4, 7}}};
inline constexpr CellFace kWedgeFaces[] = {
    {3, {0, 1, 2}}, {3, {3, 4, 5}}, {4, {0, 1, 4, 3}}, {4, {1, 2, 5, 4}}, {4, {2, 0, 3, 5}}};
inline constexpr CellFace kPyramidFaces[] = {
    {4, {0, 1, 2, 3}}, {3, {0, 1, 4}}, {3, {1, 2, 4}}, {3, {2, 3, 4}}, {3, {3, 0, 4}}};

// The edges of the linear cells, each once, as pairs of positions in the node list.
using CellEdge = std::array<int, 2>;
inline constexpr CellEdge kTetraEdges[] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
inline constexpr CellEdge kHexahedronEdges[] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                                {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
inline constexpr CellEdge kWedgeEdges[] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5},
                                           {5, 3}, {0, 3}, {1, 4}, {2, 5}};
inline constexpr CellEdge kPyramidEdges[] = {{0, 1}, {1, 2}, {2, 3}, {3, 0},
                                             {0, 4}, {1, 4}, {2, 4}, {3, 4}};

// The edges of a linear cell given its faces (linear_cell_faces below).
inline std::span<const CellEdge> edges_of(std::span<const CellFace> faces) {
  switch (faces.size()) {
    case 4:
      return kTetraEdges;
    case 6:
      return kHexahedronEdges;
    case 5:
      return faces[0].count == 3 ? std::span<const CellEdge>(kWedgeEdges)
                                 : std::span<const CellEdge>(kPyramidEdges);
  }
  return {};
}

// The faces of a linear cell of this type and node count; none for a quadratic cell or a node
// count that does not fit the type.
inline std::span<const CellFace> linear_cell_faces(CellType type, std::size_t nodes) {
  const auto when = [nodes](std::size_t count, std::span<const CellFace> faces) {
    return nodes == count ? faces : std::span<const CellFace>();
  };
  switch (type) {
    case CellType::tetra:
    case CellType::lagrange_tetrahedron:
      return when(4, kTetraFaces);
    case CellType::hexahedron:
    case CellType::lagrange_hexahedron:
      return when(8, kHexahedronFaces);
    case CellType::wedge:
      return when(6, kWedgeFaces);
    case CellType::pyramid:
      return when(5, kPyramidFaces);
    case CellType::quadratic_tetra:
      return {};
  }
  return {};
}

}  // namespace tetray
