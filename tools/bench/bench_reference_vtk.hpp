// The extract-then-trace reference, first half: VTK's vtkContour3DLinearGrid extracts the same
// isosurface from the same tets and field as triangles.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include "scenes/box_mesh.hpp"

namespace tetray::bench {

// A grid of the tets (4 point indices each) that views them without a copy; `tets` must outlive
// it. set_grid_step gives it the step's points (xyz interleaved) and point field "f", also viewed.
vtkSmartPointer<vtkUnstructuredGrid> make_grid(const std::vector<std::int64_t>& tets);
void set_grid_step(vtkUnstructuredGrid& grid, const std::vector<double>& points,
                   const std::vector<double>& field);

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

// The contour filter kept across time steps, as an extract-then-render pipeline keeps it: each
// step its input grid views that step's points and field (no copy), and only the filter's run
// is timed.
class Contour {
 public:
  // `tets` (4 point indices per tet) must outlive the contour: its grid views them.
  Contour(const std::vector<std::int64_t>& tets, double iso);
  ~Contour();
  Contour(const Contour&) = delete;
  Contour& operator=(const Contour&) = delete;

  // Points (xyz interleaved) and field of the step; both must outlive the next run.
  void set_step(const std::vector<double>& points, const std::vector<double>& field);
  double run_ms();                 // the filter's run on the step set last
  TriangleSoup triangles() const;  // of the last run

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tetray::bench
