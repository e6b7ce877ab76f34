// Clipping and shadows through the adaptor on a split mesh: the gyroid-twist scene with a clip
// box and plane, a shadowing point light and a shadowing directional light, rendered by rank 0
// alone and by all ranks with the tets split into slabs, gives the same PNG (pixels that differ
// only where two tets tie in depth, as in tests/render/composite/split_mesh_mpi_test.cpp), and
// the shadows are there: the image differs from the one without them.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <string>
#include <vector>

#include "scenes/box_mesh.hpp"
#include "shared_dir.hpp"
#include "slab_partition.hpp"
#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

const GyroidTwist& scene() {
  static const GyroidTwist gyroid = make_gyroid_twist(10, 0.2);
  return gyroid;
}

std::string config(const std::string& directory, bool shadows) {
  const std::string on = shadows ? "true" : "false";
  return "output: {directory: " + directory +
         ", formats: [png], quiet: true}\n"
         "scenes:\n"
         "  - name: lit\n"
         "    field: f\n"
         "    isovalues: [0, 0.5]\n"
         "    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: 96, height: 96}\n"
         "    clip:\n"
         "      box: {min: [-2, -2, -2], max: [0.3, 2, 2]}\n"
         "      planes: [{point: [0, 0.5, 0], normal: [0.2, 1, 0.1]}]\n"
         "    lights: [{type: headlight},\n"
         "             {type: point, position: [2, 3, 1.5], shadows: " +
         on +
         "},\n"
         "             {type: directional, direction: [-1, -0.4, -2], shadows: " +
         on + "}]\n";
}

void render(MPI_Comm comm, const std::string& directory, bool shadows,
            const std::vector<std::int64_t>& tets) {
  const MeshView mesh{PointsView::of(std::span<const double>(scene().mesh.points)),
                      TetsView::of(std::span<const std::int64_t>(tets))};
  const FieldView fields[] = {FieldView::of("f", std::span<const double>(scene().field))};
  render_step_zero(comm, config(directory, shadows), mesh, fields);
}

TEST(ShadingAcrossRanks, ClipAndShadowsGiveTheImageOfOneRank) {
  const SharedDir shared("shading_across_ranks");
  if (rank() == 0) {
    render(MPI_COMM_SELF, shared.path() + "/one", true, scene().mesh.tets);
    render(MPI_COMM_SELF, shared.path() + "/unshadowed", false, scene().mesh.tets);
  }
  render(MPI_COMM_WORLD, shared.path() + "/split", true,
         x_slab(scene().mesh, rank(), world_size()).tets);
  if (rank() != 0) return;
  const PngPixels one = read_png_rgba8(shared.path() + "/one/lit/lit_000000.png");
  const PngPixels split = read_png_rgba8(shared.path() + "/split/lit/lit_000000.png");
  const PngPixels unshadowed = read_png_rgba8(shared.path() + "/unshadowed/lit/lit_000000.png");
  ASSERT_TRUE(one.error.empty() && split.error.empty() && unshadowed.error.empty())
      << one.error << split.error << unshadowed.error;
  ASSERT_EQ(one.rgba.size(), split.rgba.size());
  const std::size_t pixels = one.rgba.size() / 4;
  EXPECT_LE(differing_pixels(one, split), pixels / 1000);
  EXPECT_GT(differing_pixels(one, unshadowed), pixels / 20) << "the lights must cast shadows";
}

}  // namespace
}  // namespace tetray::testing
