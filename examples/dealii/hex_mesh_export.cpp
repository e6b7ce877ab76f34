// deal.II's mesh as tetray's cells: each locally owned or ghost active cell becomes a
// VTK_HEXAHEDRON over the vertices it uses, numbered compactly in the order they are met.
// deal.II numbers a hexahedron's vertices lexicographically (x fastest, then y, then z); VTK goes
// round the bottom face, then round the top one.
#include <array>

#include "heat_problem.hpp"
#include "heat_state.hpp"

namespace {

constexpr std::uint8_t vtk_hexahedron = 12;
constexpr std::uint8_t vtk_duplicate_cell = 1;  // vtkGhostType: drawn by the cell's owner only
// VTK corner k is deal.II vertex dealii_vertex_of_vtk_corner[k].
constexpr std::array<unsigned int, 8> dealii_vertex_of_vtk_corner = {0, 1, 3, 2, 4, 5, 7, 6};

}  // namespace

void HeatProblem::export_mesh(LocalHexMesh& mesh) {
  HeatState& state = *state_;
  mesh = LocalHexMesh{};
  state.point_dofs.clear();
  // The rank's vertices include those of artificial cells, which are not handed over.
  std::vector<std::int64_t> point_of_vertex(state.triangulation.n_vertices(), -1);
  mesh.offsets.push_back(0);
  for (const auto& cell : state.dofs.active_cell_iterators()) {
    if (cell->is_artificial()) continue;  // neither owned nor ghost: not known here
    for (const unsigned int vertex : dealii_vertex_of_vtk_corner) {
      std::int64_t& point = point_of_vertex[cell->vertex_index(vertex)];
      if (point < 0) {
        point = static_cast<std::int64_t>(state.point_dofs.size());
        const dealii::Point<3>& x = cell->vertex(vertex);
        mesh.xyz.insert(mesh.xyz.end(), {x[0], x[1], x[2]});
        state.point_dofs.push_back(cell->vertex_dof_index(vertex, 0));
      }
      mesh.connectivity.push_back(point);
    }
    mesh.types.push_back(vtk_hexahedron);
    mesh.offsets.push_back(static_cast<std::int64_t>(mesh.connectivity.size()));
    mesh.ghost.push_back(cell->is_ghost() ? vtk_duplicate_cell : 0);
  }
}

void HeatProblem::export_temperature(LocalHexMesh& mesh) const {
  // Every DoF of an owned or ghost cell is locally relevant: its value is on this rank.
  mesh.temperature.resize(state_->point_dofs.size());
  for (std::size_t point = 0; point < state_->point_dofs.size(); ++point) {
    mesh.temperature[point] = state_->solution[state_->point_dofs[point]];
  }
}
