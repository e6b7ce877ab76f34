#include "grid_views.hpp"

#include <vector>

namespace tetray {

Status execute_grid(Adaptor& adaptor, std::int64_t step, double time, const vtkio::TetGrid& grid,
                    const Changes& changes, ExecuteReport* report) {
  MeshView mesh;
  mesh.points = PointsView::of(std::span<const double>(grid.points));
  mesh.tets = TetsView::of(std::span<const std::int64_t>(grid.tets));
  if (!grid.ghost.empty()) mesh.tets.ghost = grid.ghost.data();
  std::vector<FieldView> fields;
  for (const auto& [name, values] : grid.point_fields) {
    fields.push_back(FieldView::of(name, std::span<const double>(values)));
  }
  return adaptor.execute(step, time, mesh, fields, changes, report);
}

}  // namespace tetray
