// tetray against the brute-force reference, pixel by pixel: the
// gyroid-twist scene at small n and random fields on jittered boxes, one and several
// isosurfaces, cameras outside, inside and far away.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

// Non-square and not a multiple of the packet width, so partial packets are compared too.
const int kWidth = scaled_side(80);
const int kHeight = scaled_side(60);

AgreementCounts expect_agreement_from_cameras(const RenderScene& scene,
                                              std::span<const double> isovalues,
                                              const std::string& label) {
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  AgreementCounts total;
  int camera_index = 0;
  for (const render::Camera& camera : standard_cameras(kWidth, kHeight)) {
    total += expect_agreement(scene, camera, surfaces,
                              label + " camera " + std::to_string(camera_index++));
  }
  return total;
}

// The reference reads the renderer's vertex store, so the store must hold the solver's data:
// each tet (found by its id) keeps its points (through point_vertex, the store's own order),
// and every point its coordinates and value to float precision.
TEST(ReferenceAgreement, VolumeHoldsTheSolverData) {
  const GyroidTwist scene_data = gyroid(5);
  const RenderScene scene =
      load_scene(scene_data.mesh.points, scene_data.mesh.tets, scene_data.field);
  const render::TetVolume& volume = scene.volume;
  ASSERT_EQ(volume.tets.size(), scene_data.mesh.tet_count());
  ASSERT_EQ(volume.tet_ids.size(), volume.tets.size());
  std::vector<int> seen(volume.tets.size(), 0);
  for (std::size_t k = 0; k < volume.tets.size(); ++k) {
    const std::uint32_t id = volume.tet_ids[k];
    ASSERT_LT(id, volume.tets.size());
    ++seen[id];
    for (int c = 0; c < 4; ++c) {
      const std::int64_t point = scene_data.mesh.tets[4 * id + c];
      const std::int32_t vertex = volume.tets[k].v[c];
      ASSERT_EQ(volume.point_vertex[point], static_cast<std::uint32_t>(vertex)) << "tet " << id;
      const render::Vertex& v = volume.vertices[vertex];
      const double local[3] = {v.x, v.y, v.z};
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(volume.origin[axis] + local[axis], scene_data.mesh.points[3 * point + axis],
                    1e-6);
      }
      EXPECT_NEAR(v.f, scene_data.field[point], 1e-6);
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(seen.size()));
}

TEST(ReferenceAgreement, GyroidTwist) {
  const std::vector<std::vector<double>> isovalue_sets = {{0.0}, {0.0, 0.5}, {-0.6, 0.05, 0.7}};
  AgreementCounts total;
  for (const int n : {4, 6, 8}) {
    const GyroidTwist data = gyroid(n);
    const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
    for (std::size_t s = 0; s < isovalue_sets.size(); ++s) {
      total += expect_agreement_from_cameras(
          scene, isovalue_sets[s], "gyroid n=" + std::to_string(n) + " set " + std::to_string(s));
    }
  }
  std::cout << "[ agreement ] gyroid total: " << total.summary() << "\n";
}

TEST(ReferenceAgreement, RandomFieldsOnJitteredBoxes) {
  const std::vector<std::vector<double>> isovalue_sets = {{0.1}, {-0.4, 0.0, 0.45}};
  AgreementCounts total;
  for (const unsigned seed : {1u, 2u, 3u}) {
    const BoxMesh mesh = jittered_box(4 + static_cast<int>(seed), 0.15 + 0.05 * seed);
    const std::vector<double> field = random_field(mesh.point_count(), seed);
    const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
    for (std::size_t s = 0; s < isovalue_sets.size(); ++s) {
      total += expect_agreement_from_cameras(
          scene, isovalue_sets[s],
          "random seed " + std::to_string(seed) + " set " + std::to_string(s));
    }
  }
  std::cout << "[ agreement ] random total: " << total.summary() << "\n";
}

// Up to the renderer's maximum of isosurfaces in one trace: the nearest must win everywhere.
TEST(ReferenceAgreement, ManyIsovaluesNearestWins) {
  for (const int count : {8, render::kMaxIsovalues}) {
    std::vector<double> isovalues;
    for (int k = 0; k < count; ++k) isovalues.push_back(-0.9 + 1.8 * (k + 0.5) / count);
    const GyroidTwist data = gyroid(6);
    const RenderScene gyroid_scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
    expect_agreement_from_cameras(gyroid_scene, isovalues,
                                  "gyroid " + std::to_string(count) + " isovalues");
    const BoxMesh mesh = jittered_box(5);
    const std::vector<double> field = random_field(mesh.point_count(), 7);
    const RenderScene random_scene = load_scene(mesh.points, mesh.tets, field);
    expect_agreement_from_cameras(random_scene, isovalues,
                                  "random " + std::to_string(count) + " isovalues");
  }
}

}  // namespace
}  // namespace tetray::test
