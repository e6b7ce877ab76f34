// A volume scene end to end (run under mpirun with 1 and 3 ranks): the plane scene's box with
// a constant opacity seen head-on; every pixel's alpha in the PNG is Beer-Lambert's over the
// ray's chord through the box, and the box cut into slabs over the ranks gives the one-rank
// image bit for bit.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "plane_scene.hpp"
#include "render/scene/camera.hpp"
#include "shared_dir.hpp"
#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

constexpr double kExtinction = 0.6;  // opacity 0.3 per unit distance 0.5

std::string volume_config(const std::string& dir) {
  return "output: {directory: " + dir +
         ", quiet: true, formats: [png]}\n"
         "scenes:\n"
         "  - name: fog\n"
         "    field: f\n"
         "    volume: {colormap: grayscale, opacity: [[-1, 0.3]], unit_distance: 0.5,\n"
         "             termination: 1}\n"
         "    camera: {eye: [0.3, 0.2, 5], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: 64, height: 48}\n";
}

void run(MPI_Comm comm, const std::string& dir, const MeshView& view, const PlaneScene& scene) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, volume_config(dir), status);
  ASSERT_TRUE(status.ok()) << status.message;
  status = adaptor->execute(0, 0, view, scene.fields());
  ASSERT_TRUE(status.ok()) << status.message;
  ASSERT_TRUE(adaptor->finalize().ok());
}

double chord(render::Vec3d o, render::Vec3d d) {
  double t0 = 0, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    double lo = (-1 - o[a]) / d[a], hi = (1 - o[a]) / d[a];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
  }
  return std::max(0.0, t1 - t0);
}

TEST(VolumeScene, BeerLambertAndRankCountIndependence) {
  const SharedDir shared("volume");
  const std::string& dir = shared.path();
  const PlaneScene scene = make_plane_scene(4);
  if (rank() == 0) run(MPI_COMM_SELF, dir + "/one", scene.view(), scene);
  std::vector<std::int64_t> tets, ids;
  for (std::size_t t = 0; t < scene.mesh.tet_count(); ++t) {
    double x = 0;
    for (int v = 0; v < 4; ++v) x += 0.25 * scene.mesh.points[3 * scene.mesh.tets[4 * t + v]];
    if (std::min(world_size() - 1, static_cast<int>((x + 1) / 2 * world_size())) != rank()) {
      continue;
    }
    tets.insert(tets.end(), scene.mesh.tets.begin() + 4 * t, scene.mesh.tets.begin() + 4 * t + 4);
    ids.push_back(static_cast<std::int64_t>(t));
  }
  MeshView view = scene.view();
  view.tets = TetsView::of(std::span<const std::int64_t>(tets));
  view.tets.global_ids = ids.data();
  run(MPI_COMM_WORLD, dir + "/split", view, scene);
  if (rank() != 0) return;

  const PngPixels one = read_png_rgba8(dir + "/one/fog/fog_000000.png");
  const PngPixels split = read_png_rgba8(dir + "/split/fog/fog_000000.png");
  ASSERT_TRUE(one.error.empty()) << one.error;
  ASSERT_TRUE(split.error.empty()) << split.error;
  ASSERT_EQ(one.rgba.size(), 64u * 48 * 4);
  ASSERT_EQ(split.rgba.size(), one.rgba.size());
  render::Camera camera;
  camera.eye = {0.3, 0.2, 5};
  camera.width = 64;
  camera.height = 48;
  const render::CameraFrame frame = render::make_frame(camera);
  int covered = 0;
  for (int j = 0; j < 48; ++j) {
    for (int i = 0; i < 64; ++i) {
      const std::size_t p = 4 * (static_cast<std::size_t>(j) * 64 + i);
      const double alpha =
          1 -
          std::exp(-kExtinction * chord(camera.eye, render::pixel_direction(frame, camera, i, j)));
      EXPECT_NEAR(one.rgba[p + 3], 255 * alpha, 0.51) << i << ", " << j;
      covered += alpha > 0.5;
      for (int c = 0; c < 4; ++c) EXPECT_EQ(split.rgba[p + c], one.rgba[p + c]) << i << ", " << j;
    }
  }
  EXPECT_GT(covered, 500);
}

}  // namespace
}  // namespace tetray::testing
