// An outside solver rendering through the installed adaptor: the ball of tests/support/
// ball_image.h (radius 0.6 seen from distance 3), whose PNG must cover as many pixels as the
// camera geometry and the mesh's interpolation error allow. Exits non-zero on failure. The scene
// keeps the name `tet`, the image outside_project_test.cmake looks for.
#include <tetray/adaptor.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "ball_image.h"

namespace {

constexpr int kCells = 16, kSide = 64;
constexpr double kRadius = 0.6, kEyeDistance = 3, kFovDeg = 40;

tetray::Status render_ball(const std::string& out) {
  tetray::Status status;
  auto adaptor = tetray::Adaptor::create_from_yaml(
      MPI_COMM_WORLD,
      "output: {directory: " + out +
          ", formats: [png], quiet: true}\n"
          "scenes: [{name: tet, field: distance, isovalues: [0.6], camera: {eye: [0, 0, 3], "
          "look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}, image: {width: 64, height: 64}}]\n",
      status);
  if (!adaptor) return status;
  std::vector<double> xyz(3 * tetray_ball_point_count(kCells));
  std::vector<double> distance(tetray_ball_point_count(kCells));
  std::vector<std::int64_t> tets(4 * tetray_ball_tet_count(kCells));
  tetray_ball_mesh(kCells, xyz.data(), tets.data(), distance.data());
  const tetray::FieldView fields[] = {tetray::FieldView::of("distance", distance)};
  status =
      adaptor->execute(0, 0, {tetray::PointsView::of(xyz), tetray::TetsView::of(tets)}, fields);
  if (status.ok()) status = adaptor->finalize();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const std::string out = argc > 1 ? argv[1] : "outside_out";
  const tetray::Status status = render_ball(out);
  bool ok = status.ok();
  if (!ok) std::fprintf(stderr, "outside_solver: %s\n", status.message.c_str());
  if (ok) {
    const std::int64_t covered = tetray_png_covered_pixels((out + "/tet/tet_000000.png").c_str());
    std::int64_t fewest = 0, most = 0;
    tetray_ball_pixel_bounds(kCells, kRadius, kEyeDistance, kFovDeg, kSide, kSide, &fewest, &most);
    ok = covered >= fewest && covered <= most;
    std::fprintf(ok ? stdout : stderr,
                 "outside_solver: %lld pixels covered, expected %lld to %lld\n",
                 static_cast<long long>(covered), static_cast<long long>(fewest),
                 static_cast<long long>(most));
  }
  MPI_Finalize();
  return ok ? 0 : 1;
}
