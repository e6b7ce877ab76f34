// EXR encoding of docs/architecture.md §3: R, G, B, A as half (linear, premultiplied: EXR's own
// convention) and Z as float (view-axis depth, +inf for background), scanline, in any of
// OpenEXR 3.1's compressions (exr_compression.cpp). Encoded into memory so that the file itself is
// written atomically by write_file_atomically. The lossless compressions of one or 16 lines
// (none, RLE, ZIPS, ZIP) are assembled by tetray (exr_scanlines.cpp: several times faster than
// OpenEXR's OutputFile); the others (PIZ and the lossy ones) by OpenEXR.
#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstring>
#include <exception>

#include "render/image/exr_scanlines.hpp"
#include "render/image/image_check.hpp"
#include "render/image/image_write.hpp"

namespace tetray::render {
namespace {

// ExrCompression numbers its members as OpenEXR's Imf::Compression does.
static_assert(static_cast<int>(ExrCompression::none) == Imf::NO_COMPRESSION);
static_assert(static_cast<int>(ExrCompression::zip) == Imf::ZIP_COMPRESSION);
static_assert(static_cast<int>(ExrCompression::piz) == Imf::PIZ_COMPRESSION);
static_assert(static_cast<int>(ExrCompression::dwab) == Imf::DWAB_COMPRESSION);
static_assert(static_cast<int>(ExrCompression::dwab) + 1 == Imf::NUM_COMPRESSION_METHODS);

// An Imf::OStream into a growing byte vector (OpenEXR seeks back to patch the line offsets).
class MemoryStream final : public Imf::OStream {
 public:
  explicit MemoryStream(std::vector<unsigned char>& bytes)
      : Imf::OStream("<memory>"), bytes_(bytes) {}

  void write(const char c[], int n) override {
    const std::size_t count = static_cast<std::size_t>(n);
    if (bytes_.size() < position_ + count) bytes_.resize(position_ + count);
    std::memcpy(bytes_.data() + position_, c, count);
    position_ += count;
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = static_cast<std::size_t>(pos); }

 private:
  std::vector<unsigned char>& bytes_;
  std::size_t position_ = 0;
};

Imf::Header exr_header(int width, int height, ExrCompression compression) {
  Imf::Header header(width, height);
  header.compression() = static_cast<Imf::Compression>(compression);
  // zlib's fastest level for the zlib stage of DWAA and DWAB, as exr_scanlines.cpp uses for ZIP.
  header.zipCompressionLevel() = 1;
  for (const char* name : {"R", "G", "B", "A"}) {
    header.channels().insert(name, Imf::Channel(Imf::HALF));
  }
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  return header;
}

std::vector<Imath::half> to_half(std::span<const float> values) {
  std::vector<Imath::half> halves(values.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, values.size(), std::size_t{1} << 16),
                    [&](const auto& r) {
                      for (std::size_t k = r.begin(); k < r.end(); ++k) {
                        halves[k] = Imath::half(values[k]);
                      }
                    });
  return halves;
}

void encode_into(const Framebuffer& image, ExrCompression compression,
                 std::vector<unsigned char>& bytes) {
  std::vector<Imath::half> rgba = to_half(image.rgba);
  constexpr std::size_t kPixelStride = 4 * sizeof(Imath::half);
  const std::size_t row_stride = kPixelStride * static_cast<std::size_t>(image.width);

  Imf::FrameBuffer slices;
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    char* base = reinterpret_cast<char*>(rgba.data() + c);
    slices.insert(names[c], Imf::Slice(Imf::HALF, base, kPixelStride, row_stride));
  }
  // Slice takes a mutable pointer because input files share it; OutputFile only reads.
  char* depth = reinterpret_cast<char*>(const_cast<float*>(image.depth.data()));
  slices.insert("Z", Imf::Slice(Imf::FLOAT, depth, sizeof(float),
                                sizeof(float) * static_cast<std::size_t>(image.width)));

  // Room for the uncompressed pixels (12 bytes each) and the header and line offsets: the stream
  // then grows without copying what it already holds.
  bytes.reserve(12 * image.pixel_count() + 16 * static_cast<std::size_t>(image.height) + 4096);
  MemoryStream stream(bytes);
  Imf::OutputFile file(stream, exr_header(image.width, image.height, compression));
  file.setFrameBuffer(slices);
  file.writePixels(image.height);
}

}  // namespace

EncodedImage encode_exr(const Framebuffer& image, ExrCompression compression) {
  EncodedImage encoded;
  encoded.error = framebuffer_problem(image);
  if (!encoded.ok()) return encoded;
  try {
    if (exr_scanlines_write(compression)) {
      encode_exr_scanlines(image, compression, encoded.bytes);
    } else {
      encode_into(image, compression, encoded.bytes);
    }
  } catch (const std::exception& e) {
    encoded.bytes.clear();
    encoded.error = std::string("EXR encoding failed: ") + e.what();
  }
  return encoded;
}

}  // namespace tetray::render
