#include "support/reference_comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <sstream>

namespace tetray::test {
namespace {

constexpr int kReportedFailures = 5;

bool is_background(const render::Framebuffer& image, std::size_t p) {
  return image.hit[p] == render::kNoHit;
}

bool pixel_malformed(const render::Framebuffer& image, std::size_t p) {
  const float* rgba = &image.rgba[4 * p];
  for (int c = 0; c < 4; ++c) {
    if (std::isnan(rgba[c])) return true;
  }
  const float depth = image.depth[p];
  if (std::isnan(depth)) return true;
  if (is_background(image, p)) {
    return !(std::isinf(depth) && depth > 0) || rgba[0] != 0 || rgba[1] != 0 || rgba[2] != 0 ||
           rgba[3] != 0;
  }
  return !std::isfinite(depth) || rgba[3] != 1;
}

// Lambert headlight of docs/architecture.md §3 with the default ambient term.
bool shade_matches(const float* rgba, const render::Rgb& color, double abs_cos) {
  const double ambient = render::TraceOptions{}.ambient;
  const double light = ambient + (1 - ambient) * abs_cos;
  const double expected[3] = {color.r * light, color.g * light, color.b * light};
  for (int c = 0; c < 3; ++c) {
    if (std::abs(rgba[c] - expected[c]) > kShadeTolerance) return false;
  }
  return true;
}

// The relative depth tolerance, or float rounding of positions (at the grazing-distance
// scale) magnified by the angle of incidence, whichever is larger: near the eye the relative
// tolerance drops below rounding, and at a glancing angle a tiny shift of the plane moves the
// hit far along the ray.
double depth_allowance(const ReferenceHit& ref) {
  return std::max(kDepthTolerance * std::abs(ref.depth),
                  kGrazingDistance * ref.length_scale / ref.abs_cos);
}

class PixelReporter {
 public:
  PixelReporter(const render::Framebuffer& image, const std::string& label)
      : image_(image), label_(label) {}

  void report(const char* what, std::size_t p, const ReferenceHit& ref) {
    if (reported_++ >= kReportedFailures) return;
    const int i = static_cast<int>(p % image_.width), j = static_cast<int>(p / image_.width);
    ADD_FAILURE() << label_ << ": " << what << " at pixel (" << i << ", " << j << "): tetray "
                  << (is_background(image_, p) ? "miss" : "hit") << " depth " << image_.depth[p]
                  << " tet " << image_.hit[p] << " rgba " << image_.rgba[4 * p] << ","
                  << image_.rgba[4 * p + 1] << "," << image_.rgba[4 * p + 2] << ","
                  << image_.rgba[4 * p + 3] << "; reference " << (ref.hit ? "hit" : "miss")
                  << " depth " << ref.depth << " |cos| " << ref.abs_cos << " tet " << ref.tet_id
                  << " surface " << ref.surface << " second depth " << ref.second_depth
                  << " isopolygon edge distance " << ref.isopolygon_edge_distance
                  << " tet edge distance " << ref.tet_edge_distance;
  }

 private:
  const render::Framebuffer& image_;
  const std::string& label_;
  int reported_ = 0;
};

}  // namespace

AgreementCounts& AgreementCounts::operator+=(const AgreementCounts& o) {
  pixels += o.pixels;
  reference_hits += o.reference_hits;
  grazing_exempt += o.grazing_exempt;
  near_tet_edge += o.near_tet_edge;
  depth_by_rounding += o.depth_by_rounding;
  hit_mismatches += o.hit_mismatches;
  depth_mismatches += o.depth_mismatches;
  id_mismatches += o.id_mismatches;
  shade_mismatches += o.shade_mismatches;
  malformed_pixels += o.malformed_pixels;
  return *this;
}

std::size_t AgreementCounts::failures() const {
  return hit_mismatches + depth_mismatches + id_mismatches + shade_mismatches + malformed_pixels;
}

std::string AgreementCounts::summary() const {
  std::ostringstream out;
  out << "pixels " << pixels << ", reference hits " << reference_hits << ", grazing exempt "
      << grazing_exempt << ", near a tet edge " << near_tet_edge << ", depth within rounding only "
      << depth_by_rounding << "; mismatches: hit/miss " << hit_mismatches << ", depth "
      << depth_mismatches << ", tet id " << id_mismatches << ", shade " << shade_mismatches
      << ", malformed " << malformed_pixels;
  return out.str();
}

std::size_t malformed_pixels(const render::Framebuffer& image) {
  std::size_t count = 0;
  for (std::size_t p = 0; p < image.pixel_count(); ++p) count += pixel_malformed(image, p);
  return count;
}

std::string image_difference(const render::Framebuffer& a, const render::Framebuffer& b) {
  if (a.width != b.width || a.height != b.height) return "sizes differ";
  for (std::size_t p = 0; p < a.pixel_count(); ++p) {
    const bool same = std::memcmp(&a.depth[p], &b.depth[p], sizeof(float)) == 0 &&
                      a.hit[p] == b.hit[p] &&
                      std::memcmp(&a.rgba[4 * p], &b.rgba[4 * p], 4 * sizeof(float)) == 0;
    if (!same) {
      std::ostringstream out;
      out << "pixel (" << p % a.width << ", " << p / a.width << "): depth " << a.depth[p] << " vs "
          << b.depth[p] << ", hit " << a.hit[p] << " vs " << b.hit[p] << ", red " << a.rgba[4 * p]
          << " vs " << b.rgba[4 * p];
      return out.str();
    }
  }
  return {};
}

AgreementCounts compare_with_reference(const render::Framebuffer& image,
                                       std::span<const ReferenceHit> reference,
                                       std::span<const render::IsoSurface> surfaces,
                                       const std::string& label) {
  AgreementCounts counts;
  PixelReporter reporter(image, label);
  counts.pixels = reference.size();
  EXPECT_EQ(image.pixel_count(), reference.size()) << label;
  for (std::size_t p = 0; p < std::min(image.pixel_count(), reference.size()); ++p) {
    const ReferenceHit& ref = reference[p];
    counts.reference_hits += ref.hit;
    if (pixel_malformed(image, p)) {
      ++counts.malformed_pixels;
      reporter.report("malformed pixel", p, ref);
      continue;
    }
    if (ref.isopolygon_edge_distance < kGrazingDistance ||
        ref.clip_boundary_distance < kClipBoundaryDistance) {
      ++counts.grazing_exempt;
      continue;
    }
    counts.near_tet_edge += ref.tet_edge_distance < kGrazingDistance;
    if (is_background(image, p) == ref.hit) {
      ++counts.hit_mismatches;
      reporter.report("hit/miss differs", p, ref);
      continue;
    }
    if (!ref.hit) continue;
    const double depth_error = std::abs(image.depth[p] - ref.depth);
    if (depth_error > depth_allowance(ref)) {
      ++counts.depth_mismatches;
      reporter.report("depth differs", p, ref);
      continue;
    }
    counts.depth_by_rounding += depth_error > kDepthTolerance * std::abs(ref.depth);
    // Another isopolygon within the depth tolerance may win in float: hit id and color are
    // only defined for an unambiguous nearest hit.
    if (ref.second_depth - ref.depth <= kDepthTolerance * std::abs(ref.depth)) continue;
    if (image.hit[p] != ref.tet_id) {
      ++counts.id_mismatches;
      reporter.report("hit tet differs", p, ref);
    } else if (!shade_matches(&image.rgba[4 * p], surfaces[ref.surface].color, ref.abs_cos)) {
      ++counts.shade_mismatches;
      reporter.report("shade differs", p, ref);
    }
  }
  return counts;
}

AgreementCounts expect_agreement(const RenderScene& scene, const render::Camera& camera,
                                 std::span<const render::IsoSurface> surfaces,
                                 const std::string& label) {
  const render::Framebuffer image = trace_image(scene, camera, surfaces);
  const ReferenceIntersector reference(scene.volume, isovalues_of(surfaces));
  const std::vector<ReferenceHit> expected = reference.trace_image(camera);
  const AgreementCounts counts = compare_with_reference(image, expected, surfaces, label);
  std::cout << "[ agreement ] " << label << ": " << counts.summary() << "\n";
  EXPECT_EQ(counts.failures(), 0u) << label << ": " << counts.summary();
  return counts;
}

}  // namespace tetray::test
