#include "render/update/vertex_gradients.hpp"

#include <vector>

#include "render/volume/tet_gradient.hpp"

namespace tetray::render {

void compute_vertex_gradients(TetVolume& volume) {
  std::vector<Vec3d> sum(volume.vertices.size());
  std::vector<double> weight(volume.vertices.size(), 0.0);
  for (const Tet& tet : volume.tets) {
    const WeightedGradient g = weighted_gradient(volume, tet);
    for (const std::int32_t k : tet.v) {
      sum[k] = sum[k] + g.gradient_times_weight;
      weight[k] += g.weight;
    }
  }
  volume.gradients.resize(volume.vertices.size());
  for (std::size_t k = 0; k < sum.size(); ++k) {
    volume.gradients[k] =
        weight[k] > 0 ? static_cast<Vec3f>((1 / weight[k]) * sum[k]) : Vec3f{0, 0, 0};
  }
}

}  // namespace tetray::render
