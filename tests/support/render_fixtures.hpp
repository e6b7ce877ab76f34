// Shared set-up for the renderer's correctness tests: scenes loaded through the renderer's own
// ingest path, fields, isosurfaces, cameras, and the work scale under sanitizers.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "render/volume/tet_volume.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::test {

using render::Vec3d;

// ASan+UBSan builds run several times slower: tests divide their ray counts by this.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSanitizerSlowdown = 8;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr int kSanitizerSlowdown = 8;
#else
inline constexpr int kSanitizerSlowdown = 1;
#endif
#else
inline constexpr int kSanitizerSlowdown = 1;
#endif

// An image side of `full` pixels in Release, shrunk so the pixel count drops by the slowdown.
int scaled_side(int full);

struct RenderScene {
  render::TetVolume volume;
  render::Bvh bvh;
};

// Loads points (xyz interleaved, double), tets (4 per tet) and one value per point through
// render::load_volume, as the adaptor does, building the BVH as `policy` says.
RenderScene load_scene(std::span<const double> points, std::span<const std::int64_t> tets,
                       std::span<const double> field, const render::UpdatePolicy& policy = {});

// The same data as TetVolume, built here without the renderer's ingest (float vertices
// relative to the bounding-box center, tets in input order): lets the reference be checked
// against analytic answers on its own.
render::TetVolume volume_by_hand(std::span<const double> points, std::span<const std::int64_t> tets,
                                 std::span<const double> field);

using ScalarFunction = std::function<double(Vec3d)>;
std::vector<double> sample_field(std::span<const double> points, const ScalarFunction& f);
// Independent uniform values in [-1, 1], one per point.
std::vector<double> random_field(std::size_t point_count, unsigned seed);

BoxMesh jittered_box(int cells, double jitter = 0.15);
GyroidTwist gyroid(int n);  // docs/architecture.md §6 at t = 0.2, so the twist is on

// One isosurface per value, each with its own color.
std::vector<render::IsoSurface> make_surfaces(std::span<const double> isovalues);
std::vector<double> isovalues_of(std::span<const render::IsoSurface> surfaces);

render::Camera look_at(Vec3d eye, Vec3d target, double fov_deg, int width, int height,
                       Vec3d up = {0, 1, 0});

// The gyroid-twist benchmark camera of docs/architecture.md §6, side x side pixels.
render::Camera benchmark_camera(int side);

// Cameras that exercise different ray set-ups around a mesh in [-1, 1]^3 shifted by `center`:
// outside at benchmark distance, axis-aligned, inside the mesh, and far away with a narrow view.
std::vector<render::Camera> standard_cameras(int width, int height, Vec3d center = {});

render::Framebuffer trace_image(const RenderScene& scene, const render::Camera& camera,
                                std::span<const render::IsoSurface> surfaces,
                                render::PacketSize packet = render::PacketSize::p16x16);

}  // namespace tetray::test
