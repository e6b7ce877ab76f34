#include "tools/bench_common/image_error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace tetray::bench {
namespace {

double quantile(std::vector<double>& values, double q) {
  if (values.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

ImageError image_error(const render::Framebuffer& reference, const render::Framebuffer& approximate,
                       const render::Camera& camera, int channels) {
  if (reference.rgba.size() != approximate.rgba.size() ||
      reference.hit.size() != approximate.hit.size())
    throw std::runtime_error("images of different sizes");
  const double footprint_per_depth =
      2 * std::tan(camera.fov_deg * std::numbers::pi / 360) / camera.height;
  std::vector<double> depth_errors;
  std::size_t either = 0, differ = 0;
  ImageError e;
  for (std::size_t p = 0; p < reference.pixel_count(); ++p) {
    const bool a = reference.hit[p] != render::kNoHit, b = approximate.hit[p] != render::kNoHit;
    either += a || b;
    differ += a != b;
    if (a && b)
      depth_errors.push_back(std::abs(double(reference.depth[p]) - approximate.depth[p]) /
                             (footprint_per_depth * reference.depth[p]));
    for (int c = 0; c < channels; ++c) {
      const double d = std::abs(double(reference.rgba[4 * p + c]) - approximate.rgba[4 * p + c]);
      e.color_mean += d;
      e.color_max = std::max(e.color_max, d);
    }
  }
  e.hit_miss_fraction = either ? double(differ) / double(either) : 0;
  e.depth_median_px = quantile(depth_errors, 0.5);
  e.depth_p99_px = quantile(depth_errors, 0.99);
  const double compared = double(reference.pixel_count()) * channels;
  e.color_mean = compared > 0 ? e.color_mean / compared : 0;
  return e;
}

}  // namespace tetray::bench
