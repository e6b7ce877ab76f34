// Pixel-by-pixel comparison of a tetray framebuffer with the reference intersector, under the
// tolerances of the correctness tests: hit/miss agrees except for grazing rays, depth within 1e-5
// relative (or float rounding of positions where that is larger: near the eye, at glancing angles).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "render/core/framebuffer.hpp"
#include "render/trace/trace.hpp"
#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {

inline constexpr double kDepthTolerance = 1e-5;  // relative
inline constexpr double kShadeTolerance = 2e-3;  // absolute, per channel
// Relative distance of a hit from a clip plane below which keeping it or not is float rounding
// (the renderer tests the hit point in float).
inline constexpr double kClipBoundaryDistance = 1e-5;

struct AgreementCounts {
  std::size_t pixels = 0;
  std::size_t reference_hits = 0;
  std::size_t grazing_exempt = 0;     // near an isopolygon edge: hit/miss and depth not compared
  std::size_t near_tet_edge = 0;      // compared rays that pass near a tet edge (informational)
  std::size_t depth_by_rounding = 0;  // off by more than 1e-5 relative, within rounding
  std::size_t hit_mismatches = 0;
  std::size_t depth_mismatches = 0;
  std::size_t id_mismatches = 0;  // unambiguous hits on another tet
  std::size_t shade_mismatches = 0;
  std::size_t malformed_pixels = 0;  // NaN, or depth / hit / alpha disagreeing on hit-or-not

  AgreementCounts& operator+=(const AgreementCounts& o);
  std::size_t failures() const;
  std::string summary() const;
};

// Compares and reports the first few disagreeing pixels as test failures, labelled `label`.
AgreementCounts compare_with_reference(const render::Framebuffer& image,
                                       std::span<const ReferenceHit> reference,
                                       std::span<const render::IsoSurface> surfaces,
                                       const std::string& label);

// Checks that every pixel is well-formed: no NaN, and depth, hit key and alpha agree on
// whether the pixel is background. Returns the number of malformed pixels.
std::size_t malformed_pixels(const render::Framebuffer& image);

// Empty when the two images are bitwise identical (rgba, depth and hit); otherwise where they
// first differ.
std::string image_difference(const render::Framebuffer& a, const render::Framebuffer& b);

// Traces `camera` with tetray and the reference, compares, and prints the counts.
AgreementCounts expect_agreement(const RenderScene& scene, const render::Camera& camera,
                                 std::span<const render::IsoSurface> surfaces,
                                 const std::string& label);

}  // namespace tetray::test
