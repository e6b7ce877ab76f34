// The extract-then-trace reference, first half: VTK's vtkContour3DLinearGrid extracts the same
// isosurface from the same tets and field as triangles.
#pragma once

#include <cstdint>
#include <vector>

#include "tetray/box_mesh.hpp"

namespace tetray::bench {

// Unmerged triangles as Embree takes them: xyz per vertex (padded so the last vertex can be read
// as 16 bytes, as Embree's shared buffers require) and three indices per triangle.
struct TriangleSoup {
  std::vector<float> xyz;
  std::vector<std::uint32_t> indices;

  std::size_t vertex_count() const { return (xyz.size() - 1) / 3; }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

struct ContourRun {
  TriangleSoup triangles;
  double contour_ms = 0;  // the filter alone, not building its input grid
};

ContourRun contour_with_vtk(const BoxMesh& mesh, const std::vector<double>& field, double iso);

}  // namespace tetray::bench
