// PNG encoding of docs/architecture.md §3: 8-bit sRGB RGBA with straight alpha. The framebuffer
// holds linear, premultiplied color, so each pixel is un-premultiplied, then passed through the
// sRGB transfer function (IEC 61966-2-1) and rounded to the nearest 8-bit code.
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <new>

#include "render/core/srgb.hpp"
#include "render/image/image_check.hpp"
#include "render/image/image_write.hpp"

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

std::vector<std::uint8_t> to_srgb8(const Framebuffer& image) {
  static const SrgbEncoder encoder;
  std::vector<std::uint8_t> out(image.rgba.size(), 0);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    const float* px = &image.rgba[4 * p];
    const double alpha = unit_interval(px[3]);
    if (alpha == 0.0) continue;  // fully transparent: stays 0, 0, 0, 0
    for (int c = 0; c < 3; ++c) out[4 * p + c] = encoder.code(unit_interval(px[c] / alpha));
    out[4 * p + 3] = static_cast<std::uint8_t>(std::lround(alpha * 255.0));
  }
  return out;
}

// libpng reports errors by longjmp; the message is kept here for the caller.
struct PngSink {
  std::vector<unsigned char>* bytes = nullptr;
  bool out_of_memory = false;
  char message[256] = "";
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof(sink->message), "%s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

void append_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  try {
    sink->bytes->insert(sink->bytes->end(), data, data + length);
  } catch (const std::bad_alloc&) {
    sink->out_of_memory = true;  // reported after png_write_end; no longjmp out of a catch
  }
}

void flush_nothing(png_structp) {}

// Holds only trivially destructible locals, so the longjmp of on_png_error skips no destructor.
bool run_png_writer(png_structp png, png_infop info, int width, int height, int level,
                    png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_set_compression_level(png, level);
  // One fixed row filter instead of libpng's per-row adaptive choice, which costs more time than
  // zlib at the fast levels: "up" suits rendered images (smooth shading, flat background) and
  // gave smaller files than the adaptive choice at levels 1 and 6 on the gyroid scene. Without
  // compression, filtering gains nothing.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, level == 0 ? PNG_FILTER_NONE : PNG_FILTER_UP);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  return true;
}

void encode_into(const Framebuffer& image, int compression_level, EncodedImage& encoded) {
  std::vector<std::uint8_t> pixels = to_srgb8(image);
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (std::size_t j = 0; j < rows.size(); ++j) rows[j] = &pixels[4 * j * image.width];

  PngSink sink;
  sink.bytes = &encoded.bytes;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    encoded.error = "PNG encoding failed: out of memory";
    return;
  }
  png_set_write_fn(png, &sink, append_bytes, flush_nothing);
  const bool written =
      run_png_writer(png, info, image.width, image.height, compression_level, rows.data());
  png_destroy_write_struct(&png, &info);
  if (!written || sink.out_of_memory) {
    encoded.bytes.clear();
    encoded.error = std::string("PNG encoding failed: ") +
                    (sink.out_of_memory ? "out of memory" : sink.message);
  }
}

}  // namespace

EncodedImage encode_png(const Framebuffer& image, int compression_level) {
  EncodedImage encoded;
  encoded.error = framebuffer_problem(image);
  if (!encoded.ok()) return encoded;
  if (compression_level < 0 || compression_level > 9) {
    encoded.error =
        "PNG compression level " + std::to_string(compression_level) + " is outside 0..9";
    return encoded;
  }
  try {
    encode_into(image, compression_level, encoded);
  } catch (const std::bad_alloc&) {
    encoded.bytes.clear();
    encoded.error = "PNG encoding failed: out of memory";
  }
  return encoded;
}

}  // namespace tetray::render
