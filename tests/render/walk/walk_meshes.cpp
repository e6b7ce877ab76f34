#include "walk_meshes.hpp"

#include <algorithm>
#include <random>

#include "support/reference_tet.hpp"

namespace tetray::test {

BoxMesh make_walk_mesh(const MeshShape& shape) {
  BoxMesh mesh = jittered_box(shape.cells, shape.jitter);
  for (std::size_t p = 0; p < mesh.point_count(); ++p) {
    mesh.points[3 * p + 2] *= shape.squash_z;
    for (int axis = 0; axis < 3; ++axis) mesh.points[3 * p + axis] += shape.offset[axis];
  }
  if (shape.removed_fraction > 0) {
    std::mt19937 rng(shape.seed);
    std::bernoulli_distribution drop(shape.removed_fraction);
    std::vector<std::int64_t> kept;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
      if (drop(rng)) continue;
      kept.insert(kept.end(), mesh.tets.begin() + 4 * t, mesh.tets.begin() + 4 * t + 4);
    }
    mesh.tets = std::move(kept);
  }
  return mesh;
}

RenderScene load_walk_scene(const BoxMesh& mesh) {
  const std::vector<double> field = sample_field(
      mesh.points, [](Vec3d x) { return 0.3 * x.x - 0.7 * x.y + 1.1 * x.z + 0.25 * x.x * x.y; });
  return load_scene(mesh.points, mesh.tets, field);
}

std::vector<float> per_vertex(const render::TetVolume& volume, const std::vector<double>& values) {
  std::vector<float> out(volume.vertices.size());
  for (std::size_t p = 0; p < values.size(); ++p) {
    const std::uint32_t v =
        volume.point_vertex.empty() ? static_cast<std::uint32_t>(p) : volume.point_vertex[p];
    if (v != render::kNoVertex) out[v] = static_cast<float>(values[p]);
  }
  return out;
}

std::vector<CrossedTet> crossed_by_brute_force(const render::TetVolume& volume, Vec3d origin,
                                               Vec3d direction, double min_length) {
  const Ray ray{origin, normalize(direction)};
  std::vector<CrossedTet> crossed;
  for (std::size_t t = 0; t < volume.tets.size(); ++t) {
    std::array<Vec3d, 4> p{};
    std::array<double, 4> f{};
    for (int c = 0; c < 4; ++c) {
      const render::Vertex& v = volume.vertices[volume.tets[t].v[c]];
      p[c] = {v.x, v.y, v.z};
      f[c] = v.f;
    }
    const std::optional<FieldOnRay> on_ray =
        ReferenceTet(p, f, static_cast<std::uint32_t>(t)).field_on_ray(ray);
    if (!on_ray || on_ray->t_out - on_ray->t_in <= min_length) continue;
    crossed.push_back(
        {static_cast<std::uint32_t>(t), on_ray->t_in, on_ray->t_out, on_ray->f_in, on_ray->f_out});
  }
  std::sort(crossed.begin(), crossed.end(),
            [](const CrossedTet& a, const CrossedTet& b) { return a.t_in < b.t_in; });
  return crossed;
}

}  // namespace tetray::test
