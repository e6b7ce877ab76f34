#include "tetray_views.hpp"

tetray::MeshView hex_mesh_view(const LocalHexMesh& mesh, bool ghost_flags) {
  tetray::MeshView view{tetray::PointsView::of(mesh.xyz), {}};
  // Cells rather than tets: tetray splits each hexahedron, alike on every rank.
  view.cells = {mesh.types.data(),        mesh.offsets.data(),
                mesh.connectivity.data(), tetray::IndexType::int64,
                mesh.types.size(),        ghost_flags ? mesh.ghost.data() : nullptr};
  return view;
}

tetray::FieldView temperature_view(const LocalHexMesh& mesh) {
  return tetray::FieldView::of("temperature", mesh.temperature);
}
