// Coloring by a second field (color_by): the color at a hit is the colormap of that field
// interpolated at the hit point, however the renderer orders its vertices. On the plane z = 0
// with the color field x, the expected color follows from the hit's position alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "render/scene/colormap.hpp"
#include "render/update/volume_update.hpp"
#include "support/reference_camera.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

// The box mesh with its points numbered in a random order, so that nothing can line up by
// accident with the solver's numbering.
BoxMesh shuffled_box(int cells) {
  BoxMesh box = jittered_box(cells, 0.0);
  std::vector<std::int64_t> to(box.point_count());
  std::iota(to.begin(), to.end(), 0);
  std::shuffle(to.begin(), to.end(), std::mt19937(7));
  std::vector<double> points(box.points.size());
  for (std::size_t p = 0; p < to.size(); ++p)
    for (int a = 0; a < 3; ++a) points[3 * to[p] + a] = box.points[3 * p + a];
  for (auto& v : box.tets) v = to[v];
  box.points = std::move(points);
  return box;
}

TEST(ColorBy, ColorIsTheColormapOfTheFieldAtTheHit) {
  const BoxMesh box = shuffled_box(6);
  const auto f = sample_field(box.points, [](Vec3d p) { return p.z; });
  const auto x = sample_field(box.points, [](Vec3d p) { return p.x; });
  RenderScene scene = load_scene(box.points, box.tets, f);
  render::load_color_field(scene.volume, {x.data(), render::ScalarKind::f64, x.size()});
  const render::Colormap* map = render::find_colormap("grayscale");
  ASSERT_NE(map, nullptr);
  render::TraceOptions options;
  options.color_by = {map, -1.0f, 1.0f};
  render::Camera camera;
  camera.eye = {0.1, 0.2, 3.0};
  camera.look_at = {0, 0, 0};
  camera.width = camera.height = 64;
  const render::IsoSurface surfaces[] = {{0.0f, {1, 0, 0}}};
  const render::Framebuffer image =
      render::trace(scene.volume, scene.bvh, camera, surfaces, options);
  const ReferenceCamera rays(camera);
  std::size_t checked = 0;
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = image.index(i, j);
      if (image.hit[p] == render::kNoHit) continue;
      const Vec3d d = rays.pixel_direction(i, j);
      const double t = image.depth[p] / rays.depth(camera.eye + d);
      const Vec3d hit = camera.eye + t * d;
      float rgb[3];
      map->lookup(static_cast<float>((hit.x + 1) / 2), rgb);
      const double light = options.ambient + (1 - options.ambient) * std::abs(d.z);
      EXPECT_NEAR(image.rgba[4 * p], rgb[0] * light, 2e-3) << "pixel " << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, 2000u);
}

}  // namespace
}  // namespace tetray::test
