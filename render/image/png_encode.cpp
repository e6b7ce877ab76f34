// PNG encoding of docs/architecture.md §3: 8-bit sRGB RGBA with straight alpha. The framebuffer
// holds linear, premultiplied color, so each pixel is un-premultiplied, then passed through the
// sRGB transfer function (IEC 61966-2-1) and rounded to the nearest 8-bit code.
//
// The file is assembled here (PNG, ISO/IEC 15948:2004 §5 and §11): signature, IHDR, sRGB, gAMA,
// cHRM, one IDAT, IEND. Rows are converted and filtered in parallel (oneTBB, in the caller's
// arena); the zlib stream of all rows is compressed by libdeflate in one call, which at level 1
// takes about a third of zlib's level-1 time and gives smaller files (README, "Encoding").
#include <libdeflate.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <new>
#include <span>

#include "render/image/deflate_compressor.hpp"
#include "render/image/image_check.hpp"
#include "render/image/image_write.hpp"
#include "render/image/srgb8.hpp"

namespace tetray::render {
namespace {

// PNG filter types (ISO/IEC 15948 §9.2). One fixed filter instead of a per-row adaptive choice,
// which costs more than the compression at the fast levels: "up" suits rendered images (smooth
// shading, flat background) and gave smaller files than libpng's adaptive choice at levels 1
// and 6 on the gyroid scene. Without compression, filtering gains nothing.
constexpr std::uint8_t kFilterNone = 0, kFilterUp = 2;

// The filtered scanlines, each a filter byte and 4 * width bytes: the data the zlib stream holds.
// Each task converts its rows (and the row above them, which "up" subtracts) to sRGB in a buffer
// of its own and filters them from there: no sRGB copy of the whole image is made, and the rows
// are not zeroed before they are written.
struct FilteredRows {
  std::unique_ptr<std::uint8_t[]> bytes;
  std::size_t size = 0;
};

FilteredRows filtered_rows(const Framebuffer& image, bool filter_up) {
  const std::size_t width = static_cast<std::size_t>(image.width);
  const std::size_t row_bytes = 1 + 4 * width;
  FilteredRows rows{std::make_unique_for_overwrite<std::uint8_t[]>(row_bytes * image.height),
                    row_bytes * static_cast<std::size_t>(image.height)};
  constexpr int kRowsPerTask = 16;
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, kRowsPerTask), [&](const auto& r) {
    // A local copy: the byte stores below could alias the captured width, which would then be
    // reloaded per byte and keep the loop from being vectorized.
    const std::size_t n = 4 * width;
    const int first = filter_up ? std::max(r.begin() - 1, 0) : r.begin();
    std::vector<std::uint8_t> srgb(n * static_cast<std::size_t>(r.end() - first));
    to_srgb8_rows(image, first, r.end(), Srgb8Alpha::straight, srgb.data());
    for (int j = r.begin(); j < r.end(); ++j) {
      std::uint8_t* out = &rows.bytes[(n + 1) * static_cast<std::size_t>(j)];
      const std::uint8_t* now = &srgb[n * static_cast<std::size_t>(j - first)];
      out[0] = filter_up ? kFilterUp : kFilterNone;
      if (!filter_up || j == 0) {  // "up" over the row above the image, which is all zero
        std::copy(now, now + n, out + 1);
        continue;
      }
      const std::uint8_t* above = now - n;
      for (std::size_t k = 0; k < n; ++k) out[1 + k] = static_cast<std::uint8_t>(now[k] - above[k]);
    }
  });
  return rows;
}

void put_u32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<unsigned char>(v >> shift));
}

// Appends a chunk: length, type, data, and the CRC-32 of type and data (§5.3).
void put_chunk(std::vector<unsigned char>& out, const char type[4],
               std::span<const unsigned char> data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_u32(out, libdeflate_crc32(0, &out[type_at], 4 + data.size()));
}

std::vector<unsigned char> big_endian(std::initializer_list<std::uint32_t> values) {
  std::vector<unsigned char> bytes;
  for (std::uint32_t v : values) put_u32(bytes, v);
  return bytes;
}

// IHDR: 8-bit RGBA (colour type 6), deflate, adaptive filtering method 0, no interlace.
std::vector<unsigned char> header_data(const Framebuffer& image) {
  std::vector<unsigned char> data = big_endian(
      {static_cast<std::uint32_t>(image.width), static_cast<std::uint32_t>(image.height)});
  data.insert(data.end(), {8, 6, 0, 0, 0});
  return data;
}

// sRGB with perceptual intent, and the gAMA and cHRM values §11.3.3.5 recommends alongside it
// for decoders that do not know sRGB (gamma 1/2.2, the BT.709 primaries and D65 white point).
void put_color_space(std::vector<unsigned char>& out) {
  const unsigned char intent[] = {0};
  put_chunk(out, "sRGB", intent);
  put_chunk(out, "gAMA", big_endian({45455}));
  put_chunk(out, "cHRM", big_endian({31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000}));
}

void encode_into(const Framebuffer& image, int compression_level, EncodedImage& encoded) {
  const FilteredRows rows = filtered_rows(image, compression_level > 0);
  const DeflateCompressor compressor = make_deflate_compressor(compression_level);
  // Not zeroed: the bound is about the rows' size, the stream mostly a tenth of it.
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor.get(), rows.size);
  const auto buffer = std::make_unique_for_overwrite<unsigned char[]>(bound);
  const std::span<const unsigned char> stream(
      buffer.get(),
      libdeflate_zlib_compress(compressor.get(), rows.bytes.get(), rows.size, buffer.get(), bound));
  if (stream.empty() || stream.size() > 0x7fffffffu) {  // a chunk holds at most 2^31 - 1 bytes
    encoded.error = "PNG encoding failed: the compressed image exceeds one PNG chunk";
    return;
  }
  std::vector<unsigned char>& out = encoded.bytes;
  out.reserve(stream.size() + 128);
  out.assign({0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'});
  put_chunk(out, "IHDR", header_data(image));
  put_color_space(out);
  put_chunk(out, "IDAT", stream);
  put_chunk(out, "IEND", {});
}

}  // namespace

EncodedImage encode_png(const Framebuffer& image, int compression_level) {
  EncodedImage encoded;
  encoded.error = framebuffer_problem(image);
  if (!encoded.ok()) return encoded;
  if (compression_level < 0 || compression_level > kMaxPngCompression) {
    encoded.error = "PNG compression level " + std::to_string(compression_level) +
                    " is outside 0.." + std::to_string(kMaxPngCompression);
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
