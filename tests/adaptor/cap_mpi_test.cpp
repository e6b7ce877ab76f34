// Clip caps through the adaptor on a split mesh: the gyroid-twist scene cut by a box and a
// plane, capped with a second field, rendered by rank 0 alone and by all ranks with the tets
// split into slabs, gives the same PNG bit for bit (global tet ids given: the cap pixel's key is
// its tet's, so the tie rule of docs/architecture.md §3 picks the same winner on any split), and
// the cap is there: the image differs from the uncapped one. A missing cap field skips the scene.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "scenes/box_mesh.hpp"
#include "shared_dir.hpp"
#include "slab_partition.hpp"
#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

const GyroidWithTemperature& scene() {
  static const GyroidWithTemperature s = gyroid_with_temperature({0, 0.6, -0.3, 0.2});
  return s;
}

std::string config(const std::string& directory, bool cap) {
  return "output: {directory: " + directory +
         ", formats: [png], quiet: true}\n"
         "scenes:\n"
         "  - name: cut\n"
         "    field: f\n"
         "    isovalues: [0, 0.5]\n"
         "    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: 96, height: 96}\n"
         "    lights: [{type: headlight}, {type: point, position: [2, 3, 1.5]}]\n"
         "    clip:\n"
         "      box: {min: [-2, -2, -2], max: [0.3, 2, 2]}\n"
         "      planes: [{point: [0, 0.5, 0], normal: [0.2, 1, 0.1]}]\n" +
         (cap ? "      cap: {field: temperature, colormap: coolwarm, range: auto}\n" : "");
}

// The tets whose centroid's x falls in this rank's slab, with their global ids.
void render(MPI_Comm comm, const std::string& directory, bool cap, const Slab& part) {
  render_gyroid_with_temperature(comm, config(directory, cap), scene(), part);
}

TEST(CapAcrossRanks, GivesTheImageOfOneRank) {
  const SharedDir shared("cap_across_ranks");
  if (rank() == 0) {
    render(MPI_COMM_SELF, shared.path() + "/one", true, x_slab(scene().gyroid.mesh, 0, 1));
    render(MPI_COMM_SELF, shared.path() + "/uncapped", false, x_slab(scene().gyroid.mesh, 0, 1));
  }
  render(MPI_COMM_WORLD, shared.path() + "/split", true,
         x_slab(scene().gyroid.mesh, rank(), world_size()));
  if (rank() != 0) return;
  const PngPixels one = read_png_rgba8(shared.path() + "/one/cut/cut_000000.png");
  const PngPixels split = read_png_rgba8(shared.path() + "/split/cut/cut_000000.png");
  const PngPixels uncapped = read_png_rgba8(shared.path() + "/uncapped/cut/cut_000000.png");
  ASSERT_TRUE(one.error.empty() && split.error.empty() && uncapped.error.empty())
      << one.error << split.error << uncapped.error;
  ASSERT_EQ(one.rgba.size(), split.rgba.size());
  EXPECT_EQ(differing_pixels(one, split), 0u);
  EXPECT_GT(differing_pixels(one, uncapped), one.rgba.size() / 4 / 10) << "the cap must show";
}

// A cap field the solver does not pass skips the scene (on every rank), naming the field.
TEST(CapAcrossRanks, AMissingCapFieldSkipsTheScene) {
  const SharedDir shared("cap_missing_field");
  Status status;
  auto adaptor = Adaptor::create_from_yaml(MPI_COMM_WORLD, config(shared.path(), true), status);
  ASSERT_TRUE(adaptor) << status.message;
  const Slab part = x_slab(scene().gyroid.mesh, rank(), world_size());
  const MeshView mesh{PointsView::of(std::span<const double>(scene().gyroid.mesh.points)),
                      TetsView::of(std::span<const std::int64_t>(part.tets))};
  const FieldView fields[] = {FieldView::of("f", std::span<const double>(scene().gyroid.field))};
  status = adaptor->execute(0, 0, mesh, fields);
  EXPECT_EQ(status.code, StatusCode::partial) << status.message;
  EXPECT_NE(status.message.find("'temperature'"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("'cut'"), std::string::npos) << status.message;
  EXPECT_TRUE(adaptor->finalize().ok());
}

}  // namespace
}  // namespace tetray::testing
