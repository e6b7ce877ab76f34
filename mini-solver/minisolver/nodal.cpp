#include "minisolver/nodal.hpp"

namespace minisolver {

std::vector<std::uint8_t> fixed_dofs(const LocalMesh& mesh, std::uint8_t faces, int components) {
  std::vector<std::uint8_t> fixed;
  fixed.reserve(mesh.point_count() * static_cast<std::size_t>(components));
  for (const std::uint8_t f : mesh.faces)
    fixed.insert(fixed.end(), static_cast<std::size_t>(components), (f & faces) ? 1 : 0);
  return fixed;
}

std::vector<double> interpolate(const LocalMesh& mesh, int components,
                                const std::function<void(const Vec3&, double*)>& f) {
  const auto c = static_cast<std::size_t>(components);
  std::vector<double> values(c * mesh.point_count());
  for (std::size_t p = 0; p < mesh.point_count(); ++p) f(mesh.point(p), &values[c * p]);
  return values;
}

}  // namespace minisolver
