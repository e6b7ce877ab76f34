// The hanging nodes of an adaptively refined mesh, found from the mesh alone. Where a cell meets
// finer neighbours (deal.II, p4est and other octree codes refine so), the neighbours' corners lie
// at the middle of the coarse cell's edges and at the centre of its quadrilateral faces, and the
// solver's field there is the coarse cell's interpolant (the hanging-node constraint: the mean of
// the edge's two ends, or of the face's four corners). Split alone, the coarse cell would cut its
// face into two triangles and the fine cells into eight, with a different field on each side: the
// isosurface would crack along every refinement interface. The split (cell_split.hpp) bisects the
// coarse cell's tets at these nodes instead, so both sides cut the face into the same triangles.
//
// A point m is the hanging midpoint of an edge (a, b) of a linear cell when a-m, m-b and a-b are
// all edges of cells, no cell holds all three points, and m lies near the middle of a-b (within a
// quarter of the edge's length: solvers place new vertices on curved boundaries, off the chord). A
// point c is the hanging centre of a quadrilateral face when the face's four edges have hanging
// midpoints, c is an edge's end of all four, and c lies near the mean of the face's corners. The
// points must be shared by the cells that meet there (a solver's vertices, not a copy per cell).
// Only quadrilateral faces and edges are made conforming: a triangular face against four finer
// triangles (a tet refined into eight) cannot be matched by bisection alone. Quadratic cells take
// no part. A rank finds the hanging nodes of its cells when it holds their finer neighbours, as a
// solver's ghost layer gives (deal.II's ghost cells are every cell sharing a vertex with the
// rank's own). One level of refinement across a face is resolved (p4est's 2:1 balance); across
// an edge, any number (the split bisects the halves of an edge again).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace tetray {

class HangingNodes {
 public:
  // Finds the hanging nodes of the linear cells among [0, types.size()) (cells laid out as in
  // split_cells); xyz holds each point's position (3 per point).
  static HangingNodes find(std::span<const std::uint8_t> types,
                           std::span<const std::int64_t> offsets,
                           std::span<const std::int64_t> connectivity, std::span<const double> xyz);

  bool empty() const { return midpoints_.empty(); }
  std::size_t midpoint_count() const { return midpoints_.size(); }
  std::size_t centre_count() const { return centres_.size(); }

  // The hanging midpoint of edge (a, b), or -1.
  std::int64_t midpoint(std::int64_t a, std::int64_t b) const;
  // The hanging centre of the quadrilateral with corners a, b, c, d (any order), or -1.
  std::int64_t centre(std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) const;
  // Whether point p ends an edge with a hanging midpoint: a cell none of whose points do has no
  // hanging node (the corners of a face with a hanging centre end such edges too).
  bool ends_hanging_edge(std::int64_t p) const {
    return !edge_end_flags_.empty() && edge_end_flags_[static_cast<std::size_t>(p)] != 0;
  }
  // Whether point p is the hanging centre of a face: the split orders such points before all
  // others, so that the finer cells cut their faces through it as the coarse cell does.
  bool is_centre(std::int64_t p) const {
    return !centre_flags_.empty() && centre_flags_[static_cast<std::size_t>(p)] != 0;
  }

 private:
  struct Midpoint {
    std::int64_t a, b, mid;  // a < b
  };
  struct Centre {
    std::array<std::int64_t, 4> corners;  // sorted
    std::int64_t centre;
  };

  std::vector<Midpoint> midpoints_;  // sorted by (a, b)
  std::vector<Centre> centres_;      // sorted by corners
  std::vector<std::uint8_t> edge_end_flags_;
  std::vector<std::uint8_t> centre_flags_;
};

}  // namespace tetray
