// The gradient of the field over one linear tet, weighted by the tet's volume: what both smooth
// shading (per-vertex means) and the level-of-detail planes of the BVH nodes (per-node means)
// average.
#pragma once

#include <cmath>

#include "render/core/vec.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

struct WeightedGradient {
  Vec3d gradient_times_weight;
  double weight;  // six times the tet's volume
};

inline Vec3d to_vec3d(const Vertex& v) { return {v.x, v.y, v.z}; }

// The gradient solves [a; b; c] g = [df1, df2, df3] for the edge vectors a, b, c from vertex 0:
// g = (df1 (b x c) + df2 (c x a) + df3 (a x b)) / det. Weighting by |det| cancels the division,
// so flat tets add nothing instead of dividing by zero.
inline WeightedGradient weighted_gradient(const TetVolume& volume, const Tet& tet) {
  const Vertex* v[4];
  for (int k = 0; k < 4; ++k) v[k] = &volume.vertices[tet.v[k]];
  const Vec3d p0 = to_vec3d(*v[0]);
  const Vec3d a = to_vec3d(*v[1]) - p0, b = to_vec3d(*v[2]) - p0, c = to_vec3d(*v[3]) - p0;
  const double df1 = double(v[1]->f) - v[0]->f, df2 = double(v[2]->f) - v[0]->f,
               df3 = double(v[3]->f) - v[0]->f;
  const Vec3d bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
  const double det = dot(a, bc);
  const double sign = det < 0 ? -1.0 : 1.0;
  return {sign * (df1 * bc + df2 * ca + df3 * ab), std::abs(det)};
}

}  // namespace tetray::render
