#include "render/update/vertex_gradients.hpp"

#include <cmath>
#include <vector>

namespace tetray::render {
namespace {

Vec3d position(const Vertex& v) { return {v.x, v.y, v.z}; }

struct WeightedGradient {
  Vec3d gradient_times_weight;
  double weight;  // six times the tet's volume
};

// The gradient solves [a; b; c] g = [df1, df2, df3] for the edge vectors a, b, c from vertex 0:
// g = (df1 (b x c) + df2 (c x a) + df3 (a x b)) / det. Weighting by |det| cancels the division,
// so flat tets add nothing instead of dividing by zero.
WeightedGradient weighted_gradient(const TetVolume& volume, const Tet& tet) {
  const Vertex* v[4];
  for (int k = 0; k < 4; ++k) v[k] = &volume.vertices[tet.v[k]];
  const Vec3d p0 = position(*v[0]);
  const Vec3d a = position(*v[1]) - p0, b = position(*v[2]) - p0, c = position(*v[3]) - p0;
  const double df1 = double(v[1]->f) - v[0]->f, df2 = double(v[2]->f) - v[0]->f,
               df3 = double(v[3]->f) - v[0]->f;
  const Vec3d bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
  const double det = dot(a, bc);
  const double sign = det < 0 ? -1.0 : 1.0;
  return {sign * (df1 * bc + df2 * ca + df3 * ab), std::abs(det)};
}

}  // namespace

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
