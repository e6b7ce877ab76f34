// Smooth shading on a split mesh through the adaptor (docs/architecture.md, "Smooth shading
// across ranks"; the protocol's own test is tests/render/parallel/shared_gradients_mpi_test.cpp):
// the gyroid-twist scene, smooth, transparent, clipped and shadowed, rendered by all ranks gives
// the PNG and EXR of rank 0 alone, at the first step and at a second one that moves the points
// and changes the field; and a vertex whose gradient needs its tet count over all ranks
// (support/count_star.hpp) is shaded as one rank shades it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "scenes/box_mesh.hpp"
#include "shared_dir.hpp"
#include "slab_partition.hpp"
#include "support/count_star.hpp"
#include "support/png_read.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

const GyroidTwist& scene() {
  static const GyroidTwist gyroid = make_gyroid_twist(10, 0.2);
  return gyroid;
}

std::string config(const std::string& directory, const std::string& shading) {
  return "output: {directory: " + directory +
         ", formats: [png, exr], quiet: true}\n"
         "scenes:\n"
         "  - name: smooth\n"
         "    field: f\n"
         "    isovalues: [-0.5, 0, 0.5]\n"
         "    shading: " +
         shading +
         "\n"
         "    opacity: [0.5, 1, 0.6]\n"
         "    max_layers: 3\n"
         "    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: 96, height: 96}\n"
         "    clip:\n"
         "      box: {min: [-2, -2, -2], max: [0.3, 2, 2]}\n"
         "      planes: [{point: [0, 0.5, 0], normal: [0.2, 1, 0.1]}]\n"
         "    lights: [{type: headlight},\n"
         "             {type: point, position: [2, 3, 1.5], shadows: true},\n"
         "             {type: directional, direction: [-1, -0.4, -2], shadows: true}]\n";
}

void render(MPI_Comm comm, const std::string& directory, const std::string& shading,
            const std::vector<std::int64_t>& tets) {
  const MeshView mesh{PointsView::of(std::span<const double>(scene().mesh.points)),
                      TetsView::of(std::span<const std::int64_t>(tets))};
  const FieldView fields[] = {FieldView::of("f", std::span<const double>(scene().field))};
  render_step_zero(comm, config(directory, shading), mesh, fields);
}

// Steps 0 and 1 of the twisting gyroid (t = 0.2, then 0.6: new coordinates and field on the
// same topology, so step 1 refits and finds the shared vertices of step 0).
void render_two_steps(MPI_Comm comm, const std::string& directory,
                      const std::vector<std::int64_t>& tets) {
  Status status;
  auto adaptor = Adaptor::create_from_yaml(comm, config(directory, "smooth"), status);
  ASSERT_TRUE(adaptor) << status.message;
  std::vector<double> points = scene().mesh.points, field = scene().field;
  for (int step = 0; step < 2; ++step) {
    if (step == 1) deform_gyroid_twist(scene().mesh, 0.6, points, field);
    const MeshView mesh{PointsView::of(std::span<const double>(points)),
                        TetsView::of(std::span<const std::int64_t>(tets))};
    const FieldView fields[] = {FieldView::of("f", std::span<const double>(field))};
    const Changes changes{step == 1, step == 0, true};
    ASSERT_TRUE(adaptor->execute(step, step, mesh, fields, changes).ok());
  }
  ASSERT_TRUE(adaptor->finalize().ok());
}

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(SmoothAcrossRanks, SmoothShadingGivesTheImageOfOneRank) {
  const SharedDir shared("smooth_across_ranks");
  const std::string one = shared.path() + "/one", split = shared.path() + "/split";
  const std::string file = "/smooth/smooth_000000.";
  if (rank() == 0) {
    render(MPI_COMM_SELF, one, "smooth", scene().mesh.tets);
    render(MPI_COMM_SELF, shared.path() + "/flat", "flat", scene().mesh.tets);
  }
  render(MPI_COMM_WORLD, split, "smooth", x_slab(scene().mesh, rank(), world_size()).tets);
  if (rank() != 0) return;
  const PngPixels whole = read_png_rgba8(one + file + "png");
  const PngPixels parts = read_png_rgba8(split + file + "png");
  const PngPixels flat = read_png_rgba8(shared.path() + "/flat" + file + "png");
  ASSERT_TRUE(whole.error.empty() && parts.error.empty() && flat.error.empty())
      << whole.error << parts.error << flat.error;
  ASSERT_EQ(whole.rgba.size(), parts.rgba.size());
  EXPECT_EQ(differing_pixels(whole, parts), 0u) << "on " << world_size() << " ranks";
  EXPECT_TRUE(bytes(one + file + "exr") == bytes(split + file + "exr"))
      << "the EXR on " << world_size() << " ranks";
  EXPECT_GT(differing_pixels(whole, flat), whole.rgba.size() / 4 / 5) << "smooth must show";
}

// Needs a rank with tets and one without: ctest leaves the suite out on one rank.
TEST(SmoothOnTwoRanks, ARankWithoutTetsChangesNothing) {
  ASSERT_GE(world_size(), 2) << "needs a rank with tets and one without";
  const SharedDir shared("smooth_empty_rank");
  const std::string one = shared.path() + "/one", split = shared.path() + "/split";
  if (rank() == 0) render(MPI_COMM_SELF, one, "smooth", scene().mesh.tets);
  const int last = world_size() - 1;
  render(MPI_COMM_WORLD, split, "smooth",
         rank() == last ? std::vector<std::int64_t>{} : x_slab(scene().mesh, rank(), last).tets);
  if (rank() != 0) return;
  const std::string file = "/smooth/smooth_000000.png";
  EXPECT_FALSE(bytes(one + file).empty());
  EXPECT_TRUE(bytes(one + file) == bytes(split + file)) << "on " << world_size() << " ranks";
}

TEST(SmoothAcrossRanks, ANewStepKeepsTheImageOfOneRank) {
  const SharedDir shared("smooth_second_step");
  const std::string one = shared.path() + "/one", split = shared.path() + "/split";
  if (rank() == 0) render_two_steps(MPI_COMM_SELF, one, scene().mesh.tets);
  render_two_steps(MPI_COMM_WORLD, split, x_slab(scene().mesh, rank(), world_size()).tets);
  if (rank() != 0) return;
  const std::string file = "/smooth/smooth_000001.";
  EXPECT_FALSE(bytes(one + file + "png").empty());
  EXPECT_TRUE(bytes(one + file + "png") == bytes(split + file + "png"))
      << "on " << world_size() << " ranks";
  EXPECT_TRUE(bytes(one + "/smooth/smooth_000000.png") != bytes(one + file + "png"))
      << "step 1 must show the new step";
}

// The view tet of the count star seen from +x, its isosurface 0.25 a quad whose normals near
// vertex 0 follow that vertex's gradient: (0, -1, 0) / S on the grid of its nine tets, 45 degrees
// away from (1, -1, 0) / S, which a rank rounding on its own three tets' grid would use.
std::string star_config(const std::string& directory) {
  return "output: {directory: " + directory +
         ", formats: [png], quiet: true}\n"
         "scenes:\n"
         "  - name: star\n"
         "    field: f\n"
         "    isovalues: [0.25]\n"
         "    shading: smooth\n"
         "    camera: {eye: [3, -0.3, -0.3], look_at: [0.25, -0.3, -0.3], up: [0, 1, 0], "
         "fov_deg: 40}\n"
         "    image: {width: 64, height: 64}\n";
}

void render_star(MPI_Comm comm, const std::string& directory,
                 const std::vector<std::int64_t>& tets) {
  const CountStar star = count_star();
  const MeshView mesh{PointsView::of(std::span<const double>(star.points)),
                      TetsView::of(std::span<const std::int64_t>(tets))};
  const FieldView fields[] = {FieldView::of("f", std::span<const double>(star.field))};
  render_step_zero(comm, star_config(directory), mesh, fields);
}

TEST(SmoothAcrossRanks, AVertexSharedByRanksIsShadedOnTheGridOfAllItsTets) {
  const SharedDir shared("smooth_count_star");
  const std::string one = shared.path() + "/one", split = shared.path() + "/split";
  const CountStar star = count_star();
  if (rank() == 0) render_star(MPI_COMM_SELF, one, star.tets);
  render_star(MPI_COMM_WORLD, split, star.tets_of(rank(), world_size()));
  if (rank() != 0) return;
  const std::string file = "/star/star_000000.png";
  const PngPixels whole = read_png_rgba8(one + file);
  const PngPixels parts = read_png_rgba8(split + file);
  ASSERT_TRUE(whole.error.empty() && parts.error.empty()) << whole.error << parts.error;
  std::size_t drawn = 0;
  for (std::size_t p = 3; p < whole.rgba.size(); p += 4) drawn += whole.rgba[p] > 0;
  EXPECT_GT(drawn, whole.rgba.size() / 4 / 20) << "the star must show";
  EXPECT_EQ(differing_pixels(whole, parts), 0u) << "on " << world_size() << " ranks";
}

}  // namespace
}  // namespace tetray::testing
