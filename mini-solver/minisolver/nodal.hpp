// Per-tet and per-dof arrays from materials, faces and functions of position.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "minisolver/local_mesh.hpp"

namespace minisolver {

// One value per tet from a per-material property.
template <class Material, class Property>
std::vector<double> per_tet(const LocalMesh& mesh, const std::vector<Material>& materials,
                            Property property) {
  std::vector<double> values(mesh.tet_count());
  for (std::size_t t = 0; t < values.size(); ++t)
    values[t] = property(materials.at(mesh.material[t]));
  return values;
}

// Per-dof flags: 1 where the point lies on one of `faces`.
std::vector<std::uint8_t> fixed_dofs(const LocalMesh& mesh, std::uint8_t faces, int components);

// The nodal values of a `components`-valued function.
std::vector<double> interpolate(const LocalMesh& mesh, int components,
                                const std::function<void(const Vec3&, double*)>& f);

}  // namespace minisolver
