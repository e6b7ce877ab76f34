// The watertightness check of docs/architecture.md §5, shared by the renderer's own test
// (tests/render/trace/watertight_test.cpp) and the test of the cells the adaptor splits into tets:
// every ray whose exact path passes through the enclosed region {f_PL < iso} (decided in double
// by the reference, with a small margin) must hit the surface, with every packet size.
#pragma once

#include <array>
#include <cstddef>
#include <random>
#include <span>
#include <string>

#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {

// The ray must dip this far below the isovalue (f has unit gradient here, so it is also a
// length): far above float rounding, far below a tet.
inline constexpr double kRegionMargin = 1e-5;

inline constexpr auto kPackets = render::kPacketSizes;

struct MissCounts {
  std::size_t rays = 0;                               // rays through the enclosed region
  std::size_t crossing_from_inside = 0;               // of those, from an eye inside it
  std::array<std::size_t, kPackets.size()> misses{};  // per packet size
};

// Counts the misses among the rays through the region, and reports the first few with the
// reference's view of the ray (how close it passes to an isopolygon edge).
void count_misses(const RenderScene& scene, const BelowLevelProbe& probe,
                  const render::Camera& camera, std::span<const render::IsoSurface> surfaces,
                  bool eye_inside, const std::string& label, MissCounts& counts);

void print_counts(const std::string& label, const MissCounts& counts);

enum class EyePlace { outside_mesh, inside_mesh, inside_region };

// A camera whose view the region of radius `radius` around `center` (roughly) fills: from
// outside the region it aims near the center with the region's angular size; from inside it
// looks anywhere.
render::Camera random_camera(std::mt19937& rng, EyePlace place, Vec3d center, double radius,
                             int width, int height);

// Counts misses of `cameras` random cameras around the sphere level set `iso` of the distance to
// `center` (half outside the mesh, a quarter inside it, a quarter inside the sphere), and checks
// that there are none; `min_rays` rays must pass through the sphere.
void expect_sphere_watertight(const RenderScene& scene, Vec3d center, double iso, int cameras,
                              std::size_t min_rays, const std::string& label);

}  // namespace tetray::test
