#include "mesh_input.hpp"

#include "scenes/box_mesh.hpp"

namespace minisolver {
namespace {

Mesh box_mesh(const MeshConfig& config) {
  tetray::BoxMesh box = tetray::make_box_mesh({config.cells, config.lo, config.hi, config.jitter});
  Mesh mesh;
  mesh.points = std::move(box.points);
  mesh.tets = std::move(box.tets);
  mesh.material.assign(mesh.tet_count(), 0);
  mesh.faces.reserve(mesh.point_count());
  const auto& c = config.cells;
  for (int k = 0; k <= c[2]; ++k)
    for (int j = 0; j <= c[1]; ++j)
      for (int i = 0; i <= c[0]; ++i) mesh.faces.push_back(grid_point_faces({i, j, k}, c));
  return mesh;
}

Mesh shaped_mesh(const MeshConfig& config) {
  switch (config.kind) {
    case MeshKind::box:
      return box_mesh(config);
    case MeshKind::shell:
      return make_shell_sector(config.cells, config.shell);
    case MeshKind::beam:
      break;
  }
  return make_beam(config.cells, config.lo, config.hi);
}

}  // namespace

Mesh make_mesh(const SolverConfig& config) {
  Mesh mesh = shaped_mesh(config.mesh);
  if (const auto& region = config.stiff_region) split_materials(mesh, region->axis, region->above);
  return mesh;
}

}  // namespace minisolver
