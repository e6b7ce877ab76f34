#include "minisolver/assembly.hpp"

namespace minisolver {

ElasticBlock elastic_element_matrix(const TetGeometry& g, const Lame& lame) {
  ElasticBlock k{};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const Vec3 &ga = g.gradient[a], &gb = g.gradient[b];
      const double shear = lame.mu * dot(ga, gb);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          k[(3 * a + i) * 12 + 3 * b + j] =
              g.volume *
              (lame.lambda * ga[i] * gb[j] + lame.mu * ga[j] * gb[i] + (i == j ? shear : 0));
    }
  return k;
}

CsrMatrix assemble_diffusion(const LocalMesh& mesh, std::shared_ptr<const SparsePattern> pattern,
                             std::span<const double> coefficient) {
  CsrMatrix k(std::move(pattern));
  std::array<double, 16> block{};
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const TetGeometry g = tet_geometry(mesh.tet_points(t));
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        block[4 * a + b] = coefficient[t] * g.volume * dot(g.gradient[a], g.gradient[b]);
    k.add_element(&mesh.tets[4 * t], block);
  }
  return k;
}

CsrMatrix assemble_mass(const LocalMesh& mesh, std::shared_ptr<const SparsePattern> pattern,
                        std::span<const double> density) {
  const int c = pattern->components;
  CsrMatrix m(std::move(pattern));
  std::vector<double> block(16 * static_cast<std::size_t>(c * c));
  const int width = 4 * c;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const double volume = signed_volume(mesh.tet_points(t));
    // P1 consistent mass: volume/20 off the diagonal, volume/10 on it.
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int i = 0; i < c; ++i)
          block[static_cast<std::size_t>((c * a + i) * width + c * b + i)] =
              density[t] * volume * (a == b ? 0.1 : 0.05);
    m.add_element(&mesh.tets[4 * t], block);
  }
  return m;
}

std::vector<double> lumped_mass(const LocalMesh& mesh, int components,
                                std::span<const double> density) {
  const auto c = static_cast<std::size_t>(components);
  std::vector<double> lumped(c * mesh.point_count(), 0.0);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const double share = density[t] * signed_volume(mesh.tet_points(t)) / 4;
    for (int a = 0; a < 4; ++a)
      for (std::size_t i = 0; i < c; ++i) lumped[c * mesh.tets[4 * t + a] + i] += share;
  }
  return lumped;
}

CsrMatrix assemble_elasticity(const LocalMesh& mesh, std::shared_ptr<const SparsePattern> pattern,
                              std::span<const Lame> lame) {
  CsrMatrix k(std::move(pattern));
  for (std::size_t t = 0; t < mesh.tet_count(); ++t)
    k.add_element(&mesh.tets[4 * t],
                  elastic_element_matrix(tet_geometry(mesh.tet_points(t)), lame[t]));
  return k;
}

}  // namespace minisolver
