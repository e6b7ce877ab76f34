// Bad input (docs/architecture.md §5): render::check_mesh names what is wrong or, under skip_tets,
// drops the tets that touch non-finite data, and the renderer then draws what is valid. Empty
// meshes and isovalues outside the field's range give the background, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "render/update/volume_update.hpp"
#include "render/volume/mesh_check.hpp"
#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct MeshArrays {
  std::vector<double> points;
  std::vector<std::int64_t> tets;
  std::vector<double> field;

  render::PointSource point_source() const {
    render::PointSource source;
    source.xyz = points.data();
    source.count = points.size() / 3;
    return source;
  }
  render::FieldSource field_source() const {
    render::FieldSource source;
    source.values = field.data();
    source.count = field.size();
    return source;
  }
  render::MeshCheck check(render::NonFinitePolicy policy, std::vector<std::uint8_t>& keep) const {
    return render::check_mesh(tets, point_source(), field_source(), policy, keep);
  }
  RenderScene load(std::span<const std::uint8_t> keep) const {
    RenderScene scene;
    render::load_volume(scene.volume, scene.bvh, tets, keep, {}, point_source(), field_source(),
                        {});
    return scene;
  }
};

MeshArrays gyroid_arrays(int n) {
  GyroidTwist data = gyroid(n);
  return {std::move(data.mesh.points), std::move(data.mesh.tets), std::move(data.field)};
}

// An interior point, so skipping its tets leaves the bounding box as it was.
constexpr std::int64_t kInteriorPoint = 2 * 25 + 2 * 5 + 2;  // (2, 2, 2) of the n = 4 grid
constexpr std::int64_t kOtherInteriorPoint = 3 * 25 + 1 * 5 + 2;

std::vector<std::uint8_t> tets_not_touching(const MeshArrays& mesh,
                                            std::initializer_list<std::int64_t> points) {
  std::vector<std::uint8_t> keep(mesh.tets.size() / 4, 1);
  for (std::size_t t = 0; t < keep.size(); ++t) {
    for (int c = 0; c < 4; ++c) {
      if (std::find(points.begin(), points.end(), mesh.tets[4 * t + c]) != points.end()) {
        keep[t] = 0;
      }
    }
  }
  return keep;
}

void expect_background(const render::Framebuffer& image, const render::Camera& camera,
                       const std::string& label) {
  EXPECT_EQ(image.width, camera.width) << label;
  EXPECT_EQ(image.height, camera.height) << label;
  EXPECT_EQ(malformed_pixels(image), 0u) << label;
  EXPECT_EQ(std::count(image.hit.begin(), image.hit.end(), render::kNoHit),
            static_cast<long>(image.pixel_count()))
      << label;
}

TEST(MeshCheck, ValidMeshPasses) {
  const MeshArrays mesh = gyroid_arrays(4);
  for (const auto policy : {render::NonFinitePolicy::error, render::NonFinitePolicy::skip_tets}) {
    std::vector<std::uint8_t> keep;
    const render::MeshCheck check = mesh.check(policy, keep);
    EXPECT_EQ(check.error, "");
    EXPECT_EQ(check.tets_out_of_range + check.nonfinite_points + check.nonfinite_values +
                  check.tets_skipped,
              0u);
    EXPECT_EQ(keep, std::vector<std::uint8_t>(mesh.tets.size() / 4, 1));
  }
}

TEST(MeshCheck, IndexOutOfRangeIsNamed) {
  MeshArrays mesh = gyroid_arrays(4);
  const std::int64_t point_count = static_cast<std::int64_t>(mesh.field.size());
  mesh.tets[4 * 37 + 2] = point_count;
  mesh.tets[4 * 90 + 0] = -1;
  std::vector<std::uint8_t> keep;
  const render::MeshCheck error = mesh.check(render::NonFinitePolicy::error, keep);
  EXPECT_NE(error.error.find("37"), std::string::npos) << error.error;
  EXPECT_GE(error.tets_out_of_range, 1u);
  // skip_tets is about non-finite data: an index out of range is either an error or a skip.
  const render::MeshCheck skip = mesh.check(render::NonFinitePolicy::skip_tets, keep);
  if (skip.error.empty()) {
    ASSERT_EQ(keep.size(), mesh.tets.size() / 4);
    EXPECT_EQ(keep[37], 0);
    EXPECT_EQ(keep[90], 0);
  }
}

TEST(MeshCheck, NonFiniteFieldValueIsNamed) {
  MeshArrays mesh = gyroid_arrays(4);
  mesh.field[kInteriorPoint] = kNaN;
  mesh.field[kOtherInteriorPoint] = kInf;
  std::vector<std::uint8_t> keep;
  const render::MeshCheck check = mesh.check(render::NonFinitePolicy::error, keep);
  EXPECT_NE(check.error.find(std::to_string(kInteriorPoint)), std::string::npos) << check.error;
}

// With skip_tets the tets touching non-finite data are dropped and counted, and the image is
// the one of the mesh without them: the reference is built from the same mesh with those
// points made finite again, which no kept tet uses.
void expect_skipped_and_rendered(const MeshArrays& bad, const MeshArrays& good,
                                 std::initializer_list<std::int64_t> bad_points,
                                 const std::string& label) {
  std::vector<std::uint8_t> keep;
  const render::MeshCheck check = bad.check(render::NonFinitePolicy::skip_tets, keep);
  EXPECT_EQ(check.error, "") << label;
  const std::vector<std::uint8_t> expected_keep = tets_not_touching(good, bad_points);
  EXPECT_EQ(keep, expected_keep) << label;
  EXPECT_EQ(check.tets_skipped,
            static_cast<std::uint64_t>(std::count(expected_keep.begin(), expected_keep.end(), 0)))
      << label;

  const RenderScene scene = bad.load(keep);
  EXPECT_EQ(scene.volume.tets.size(),
            static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1)));
  const RenderScene clean = good.load(keep);
  const double isovalues[] = {0.0};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const ReferenceIntersector reference(clean.volume, isovalues_of(surfaces));
  for (const render::Camera& camera : standard_cameras(scaled_side(48), scaled_side(40))) {
    const AgreementCounts counts = compare_with_reference(
        trace_image(scene, camera, surfaces), reference.trace_image(camera), surfaces, label);
    EXPECT_EQ(counts.failures(), 0u) << label << ": " << counts.summary();
  }
}

TEST(MeshCheck, NonFiniteFieldValuesSkipTheirTets) {
  const MeshArrays good = gyroid_arrays(4);
  MeshArrays bad = good;
  bad.field[kInteriorPoint] = kNaN;
  bad.field[kOtherInteriorPoint] = -kInf;
  std::vector<std::uint8_t> keep;
  EXPECT_EQ(bad.check(render::NonFinitePolicy::skip_tets, keep).nonfinite_values, 2u);
  expect_skipped_and_rendered(bad, good, {kInteriorPoint, kOtherInteriorPoint}, "field");
}

TEST(MeshCheck, NonFinitePointsSkipTheirTets) {
  const MeshArrays good = gyroid_arrays(4);
  MeshArrays bad = good;
  bad.points[3 * kInteriorPoint + 1] = kInf;
  bad.points[3 * kOtherInteriorPoint + 2] = kNaN;
  std::vector<std::uint8_t> keep;
  EXPECT_EQ(bad.check(render::NonFinitePolicy::skip_tets, keep).nonfinite_points, 2u);
  expect_skipped_and_rendered(bad, good, {kInteriorPoint, kOtherInteriorPoint}, "points");
}

// Without the index pass (indices checked on an earlier step), an index that went out of range
// is still never used to read a point: under skip_tets its tet is skipped with the tets that
// touch a non-finite value, and nothing else.
TEST(MeshCheck, SkippedIndexPassNeverReadsPastThePoints) {
  MeshArrays mesh = gyroid_arrays(4);
  mesh.field[kInteriorPoint] = kNaN;
  const std::size_t tet = 11;
  mesh.tets[4 * tet + 1] = static_cast<std::int64_t>(mesh.points.size() / 3) + 1000;
  std::vector<std::uint8_t> keep;
  const render::MeshCheck found = render::check_mesh(
      mesh.tets, mesh.point_source(), mesh.field_source(), render::NonFinitePolicy::skip_tets, keep,
      /*check_indices=*/false);
  EXPECT_TRUE(found.error.empty()) << found.error;
  std::vector<std::uint8_t> expected = tets_not_touching(mesh, {kInteriorPoint});
  expected[tet] = 0;
  EXPECT_EQ(keep, expected);
}

TEST(BadInput, EmptyMeshGivesTheBackground) {
  const MeshArrays no_points{};
  const MeshArrays no_tets = [] {
    MeshArrays mesh = gyroid_arrays(3);
    mesh.tets.clear();
    return mesh;
  }();
  const MeshArrays all_skipped = gyroid_arrays(3);
  const std::vector<std::uint8_t> skip_all(all_skipped.tets.size() / 4, 0);
  const double isovalues[] = {0.0};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const render::Camera camera = standard_cameras(33, 20)[0];

  for (const MeshArrays* mesh : {&no_points, &no_tets}) {
    std::vector<std::uint8_t> keep;
    EXPECT_EQ(mesh->check(render::NonFinitePolicy::error, keep).error, "");
    expect_background(trace_image(mesh->load({}), camera, surfaces), camera, "empty");
  }
  expect_background(trace_image(all_skipped.load(skip_all), camera, surfaces), camera,
                    "all skipped");
}

TEST(BadInput, IsovalueOutsideTheFieldRangeGivesTheBackground) {
  const MeshArrays mesh = gyroid_arrays(5);
  const RenderScene scene = mesh.load({});
  for (const double iso : {5.0, -5.0}) {
    const double isovalues[] = {iso};
    for (const render::Camera& camera : standard_cameras(40, 24)) {
      expect_background(trace_image(scene, camera, make_surfaces(isovalues)), camera,
                        "iso " + std::to_string(iso));
    }
  }
  for (const render::Camera& camera : standard_cameras(40, 24)) {
    expect_background(trace_image(scene, camera, {}), camera, "no isosurfaces");
  }
}

}  // namespace
}  // namespace tetray::test
