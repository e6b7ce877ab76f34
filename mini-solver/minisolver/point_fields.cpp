#include "minisolver/point_fields.hpp"

#include <cmath>

#include "minisolver/tet_geometry.hpp"

namespace minisolver {

std::vector<double> magnitudes(std::span<const double> vectors) {
  std::vector<double> m(vectors.size() / 3);
  for (std::size_t p = 0; p < m.size(); ++p)
    m[p] = std::sqrt(vectors[3 * p] * vectors[3 * p] + vectors[3 * p + 1] * vectors[3 * p + 1] +
                     vectors[3 * p + 2] * vectors[3 * p + 2]);
  return m;
}

std::vector<double> von_mises_per_tet(const LocalMesh& mesh,
                                      const std::vector<ElasticMaterial>& materials,
                                      std::span<const double> u) {
  std::vector<double> stress(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const TetGeometry g = tet_geometry(mesh.tet_points(t));
    double grad[3][3] = {};  // du_i / dx_j
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          grad[i][j] += u[3 * mesh.tets[4 * t + a] + i] * g.gradient[a][j];
    const Lame lame = materials.at(mesh.material[t]).lame();
    const double trace = grad[0][0] + grad[1][1] + grad[2][2];
    double sigma[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        sigma[i][j] = lame.mu * (grad[i][j] + grad[j][i]) + (i == j ? lame.lambda * trace : 0);
    const double mean = (sigma[0][0] + sigma[1][1] + sigma[2][2]) / 3;
    double deviatoric_squared = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double s = sigma[i][j] - (i == j ? mean : 0);
        deviatoric_squared += s * s;
      }
    stress[t] = std::sqrt(1.5 * deviatoric_squared);
  }
  return stress;
}

std::vector<double> average_to_points(const DofSpace& scalar_space,
                                      std::span<const double> per_tet) {
  const LocalMesh& mesh = scalar_space.mesh();
  std::vector<double> sum(mesh.point_count(), 0.0), weight(mesh.point_count(), 0.0);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const double volume = signed_volume(mesh.tet_points(t));
    for (int a = 0; a < 4; ++a) {
      sum[mesh.tets[4 * t + a]] += volume * per_tet[t];
      weight[mesh.tets[4 * t + a]] += volume;
    }
  }
  scalar_space.accumulate(sum);
  scalar_space.accumulate(weight);
  for (std::size_t p = 0; p < sum.size(); ++p) sum[p] /= weight[p];
  return sum;
}

std::vector<double> interior_indicator(const LocalMesh& mesh) {
  std::vector<double> inside(mesh.point_count());
  for (std::size_t p = 0; p < inside.size(); ++p) inside[p] = mesh.faces[p] == 0 ? 1.0 : 0.0;
  return inside;
}

}  // namespace minisolver
