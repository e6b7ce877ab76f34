#include "render/image/srgb8.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "render/core/srgb.hpp"

namespace tetray::render {
namespace {

// The rounded 8-bit sRGB code of a linear value, exactly as round(255 * encode(v)) but without
// a pow per channel: `thresholds[k]` is the linear value where the code steps from k to k + 1,
// and `bucket_code[i]` the code at v = i / kBuckets. The steepest part of the curve (at 0:
// 12.92 * 255 codes per unit) crosses fewer than one threshold per bucket, so the code of any v
// in bucket i is bucket_code[i] or one more.
class SrgbEncoder {
 public:
  SrgbEncoder() {
    for (std::size_t k = 0; k < thresholds_.size(); ++k) {
      thresholds_[k] = srgb_decode((static_cast<double>(k) + 0.5) / 255.0);
    }
    for (std::size_t i = 0; i < kBuckets; ++i) {
      const double v = static_cast<double>(i) / kBuckets;
      bucket_code_[i] = static_cast<std::uint8_t>(
          std::upper_bound(thresholds_.begin(), thresholds_.end(), v) - thresholds_.begin());
    }
  }

  // `linear` in [0, 1].
  std::uint8_t code(double linear) const {
    const auto bucket = std::min(static_cast<std::size_t>(linear * kBuckets), kBuckets - 1);
    const std::uint8_t code = bucket_code_[bucket];
    return static_cast<std::uint8_t>(code + (code < 255 && linear >= thresholds_[code] ? 1 : 0));
  }

 private:
  static constexpr std::size_t kBuckets = 4096;
  std::array<double, 255> thresholds_{};
  std::array<std::uint8_t, kBuckets> bucket_code_{};
};

// Clamped to [0, 1], with NaN as 0.
double unit_interval(double value) { return value > 0.0 ? std::min(value, 1.0) : 0.0; }

void straight_pixel(const SrgbEncoder& encoder, const float* rgba, std::uint8_t* out) {
  const double alpha = unit_interval(rgba[3]);
  if (alpha == 0.0) {
    std::fill(out, out + 4, std::uint8_t{0});  // fully transparent: 0, 0, 0, 0
    return;
  }
  if (alpha == 1.0) {  // opaque, as surfaces mostly are: dividing by 1 changes nothing
    for (int c = 0; c < 3; ++c) out[c] = encoder.code(unit_interval(rgba[c]));
    out[3] = 255;
    return;
  }
  for (int c = 0; c < 3; ++c) out[c] = encoder.code(unit_interval(rgba[c] / alpha));
  out[3] = static_cast<std::uint8_t>(std::lround(alpha * 255.0));
}

}  // namespace

void to_srgb8_rows(const Framebuffer& image, int first, int last, Srgb8Alpha alpha,
                   std::uint8_t* out) {
  static const SrgbEncoder encoder;
  const std::size_t begin = static_cast<std::size_t>(first) * image.width;
  const std::size_t end = static_cast<std::size_t>(last) * image.width;
  for (std::size_t p = begin; p < end; ++p) {
    const float* rgba = &image.rgba[4 * p];
    if (alpha == Srgb8Alpha::straight) {
      straight_pixel(encoder, rgba, out);
      out += 4;
    } else {
      for (int c = 0; c < 3; ++c) *out++ = encoder.code(unit_interval(rgba[c]));
    }
  }
}

std::vector<std::uint8_t> to_srgb8(const Framebuffer& image, Srgb8Alpha alpha) {
  const std::size_t channels = alpha == Srgb8Alpha::straight ? 4 : 3;
  const std::size_t row_bytes = channels * static_cast<std::size_t>(image.width);
  std::vector<std::uint8_t> out(row_bytes * static_cast<std::size_t>(image.height));
  constexpr int kRowsPerTask = 16;
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, kRowsPerTask), [&](const auto& rows) {
    to_srgb8_rows(image, rows.begin(), rows.end(), alpha, &out[row_bytes * rows.begin()]);
  });
  return out;
}

}  // namespace tetray::render
