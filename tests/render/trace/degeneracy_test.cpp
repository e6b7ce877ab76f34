// Ties and degeneracies: vertex values equal to the isovalue, constant fields,
// surfaces along tet faces and through vertices, inverted and zero-volume tets, and a mesh far
// from the coordinate origin. Every image must be well-formed and agree with the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

const int kWidth = scaled_side(72);
const int kHeight = scaled_side(56);

void expect_agreement_from_cameras(const RenderScene& scene, std::span<const double> isovalues,
                                   std::span<const render::Camera> cameras,
                                   const std::string& label) {
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    expect_agreement(scene, cameras[c], surfaces, label + " camera " + std::to_string(c));
  }
}

void expect_agreement_from_cameras(const RenderScene& scene, std::span<const double> isovalues,
                                   const std::string& label) {
  expect_agreement_from_cameras(scene, isovalues, standard_cameras(kWidth, kHeight), label);
}

// Odd image sizes looking down the axes and the cube diagonal: the middle rows and columns
// lie exactly in grid planes and Kuhn diagonal planes, so rays run along tet faces.
std::vector<render::Camera> aligned_cameras() {
  const int side = scaled_side(61) | 1;
  return {look_at({0, 0, 4}, {0, 0, 0}, 40, side, side),
          look_at({4, 0, 0}, {0, 0, 0}, 40, side, side),
          look_at({3, 3, 3}, {0, 0, 0}, 40, side, side, {0, 0, 1})};
}

TEST(Degeneracies, VertexValuesEqualToTheIsovalue) {
  const BoxMesh mesh = jittered_box(6);
  // Values on a grid of halves: many vertices sit exactly on each isovalue.
  std::vector<double> field = random_field(mesh.point_count(), 11);
  for (double& v : field) v = std::round(2 * v) / 2;
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  for (const double iso : {0.0, 0.5, 1.0, -1.0}) {
    const double isovalues[] = {iso};
    expect_agreement_from_cameras(scene, isovalues, "halves iso " + std::to_string(iso));
  }
}

TEST(Degeneracies, ConstantFieldsHaveNoSurface) {
  const BoxMesh mesh = jittered_box(4);
  const double iso = 0.25;
  for (const double value : {iso, iso + 0.5, iso - 0.5}) {
    const std::vector<double> field(mesh.point_count(), value);
    const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
    const double isovalues[] = {iso};
    const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
    for (const render::Camera& camera : standard_cameras(kWidth, kHeight)) {
      const render::Framebuffer image = trace_image(scene, camera, surfaces);
      EXPECT_EQ(std::count(image.hit.begin(), image.hit.end(), render::kNoHit),
                static_cast<long>(image.pixel_count()))
          << "constant " << value;
      EXPECT_EQ(malformed_pixels(image), 0u);
    }
    expect_agreement_from_cameras(scene, isovalues, "constant " + std::to_string(value));
  }
}

TEST(Degeneracies, SurfacesAlongFacesAndThroughVertices) {
  const BoxMesh mesh = jittered_box(4, 0.0);  // grid planes at multiples of 0.5
  const std::vector<double> x = sample_field(mesh.points, [](Vec3d p) { return p.x; });
  const std::vector<double> sum =
      sample_field(mesh.points, [](Vec3d p) { return p.x + p.y + p.z; });
  const RenderScene along_faces = load_scene(mesh.points, mesh.tets, x);
  const RenderScene through_vertices = load_scene(mesh.points, mesh.tets, sum);
  // Interior grid planes, the mesh's own boundary face (x = 1), and two at once.
  for (const std::vector<double>& isovalues :
       std::vector<std::vector<double>>{{0.0}, {0.5}, {1.0}, {-0.5, 0.5}}) {
    const std::string label = "f = x iso " + std::to_string(isovalues[0]);
    expect_agreement_from_cameras(along_faces, isovalues, label);
    expect_agreement_from_cameras(along_faces, isovalues, aligned_cameras(), label + " aligned");
  }
  for (const double iso : {0.0, 0.5, -1.5}) {
    const double isovalues[] = {iso};
    const std::string label = "f = x+y+z iso " + std::to_string(iso);
    expect_agreement_from_cameras(through_vertices, isovalues, label);
    expect_agreement_from_cameras(through_vertices, isovalues, aligned_cameras(),
                                  label + " aligned");
  }
}

TEST(Degeneracies, InvertedTets) {
  GyroidTwist data = gyroid(6);
  // Every other tet with two vertices swapped: the same geometry, the opposite orientation.
  for (std::size_t t = 1; t < data.mesh.tet_count(); t += 2) {
    std::swap(data.mesh.tets[4 * t + 2], data.mesh.tets[4 * t + 3]);
  }
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const double isovalues[] = {0.0, 0.5};
  expect_agreement_from_cameras(scene, isovalues, "inverted");
}

// Zero-volume tets of every kind: edges collapsed by moving a point onto its neighbor (which
// also inverts some tets around it), repeated vertex indices, four distinct coplanar points
// on the boundary, and a tet that is a single point. A flat tet's isopolygon lies in its
// plane, the limit of ever thinner slivers that keeps the surface closed.
TEST(Degeneracies, ZeroVolumeTets) {
  BoxMesh mesh = jittered_box(5);  // jitter moves interior points only: the boundary stays flat
  const std::vector<double> field = random_field(mesh.point_count(), 5);
  const auto copy_point = [&](std::int64_t to, std::int64_t from) {
    for (int axis = 0; axis < 3; ++axis) mesh.points[3 * to + axis] = mesh.points[3 * from + axis];
  };
  copy_point(mesh.point_index(2, 2, 2), mesh.point_index(3, 2, 2));
  copy_point(mesh.point_index(1, 3, 2), mesh.point_index(1, 3, 3));
  copy_point(mesh.point_index(3, 1, 3), mesh.point_index(4, 2, 4));
  const std::int64_t a = mesh.point_index(2, 3, 1), b = mesh.point_index(3, 3, 1),
                     c = mesh.point_index(2, 4, 1);
  const std::int64_t extra[][4] = {
      {a, a, b, c},
      {a, b, a, b},
      {c, c, c, c},
      {mesh.point_index(1, 1, 0), mesh.point_index(2, 1, 0), mesh.point_index(1, 2, 0),
       mesh.point_index(2, 2, 0)},
      {mesh.point_index(0, 3, 3), mesh.point_index(0, 4, 4), mesh.point_index(0, 3, 4),
       mesh.point_index(0, 4, 3)},
  };
  for (const auto& tet : extra) mesh.tets.insert(mesh.tets.end(), tet, tet + 4);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {0.0, 0.3};
  expect_agreement_from_cameras(scene, isovalues, "zero volume");
  expect_agreement_from_cameras(scene, isovalues, aligned_cameras(), "zero volume aligned");
}

// Float vertices relative to a local origin keep a mesh at 1e6 as precise as one at 0.
TEST(Degeneracies, MeshFarFromTheOrigin) {
  const Vec3d center{1e6, 1e6, 1e6};
  BoxMeshSpec spec;
  spec.cells = {6, 6, 6};
  spec.jitter = 0.15;
  for (int axis = 0; axis < 3; ++axis) {
    spec.lo[axis] = center[axis] - 1;
    spec.hi[axis] = center[axis] + 1;
  }
  const BoxMesh mesh = make_box_mesh(spec);
  const std::vector<double> field = sample_field(mesh.points, [&](Vec3d p) {
    const Vec3d q = p - center;
    return std::sin(4 * q.x) * std::cos(4 * q.y) + std::sin(4 * q.y) * std::cos(4 * q.z) +
           std::sin(4 * q.z) * std::cos(4 * q.x);
  });
  const RenderScene scene = load_scene(mesh.points, mesh.tets, field);
  const double isovalues[] = {0.0, 0.5};
  expect_agreement_from_cameras(scene, isovalues, standard_cameras(kWidth, kHeight, center),
                                "far from origin");
}

}  // namespace
}  // namespace tetray::test
