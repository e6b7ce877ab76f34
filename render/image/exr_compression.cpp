// The names and properties of OpenEXR 3.1's compressions (ImfCompression.h; the OpenEXR
// documentation's "Technical Introduction", Data Compression) as the config and the benchmark
// spell them.
#include <algorithm>
#include <array>

#include "render/image/image_write.hpp"

namespace tetray::render {
namespace {

// What each leaves of the two channel types an image holds: R, G, B, A half and Z float.
constexpr std::array<ExrCompressionInfo, 10> kCompressions{{
    {ExrCompression::none, "none", true, "uncompressed"},
    {ExrCompression::rle, "rle", true, "run-length: cheap, compresses flat areas"},
    {ExrCompression::zips, "zips", true, "zlib per scanline"},
    {ExrCompression::zip, "zip", true, "zlib per 16 scanlines"},
    {ExrCompression::piz, "piz", true, "wavelet + Huffman"},
    {ExrCompression::pxr24, "pxr24", false, "lossy: Z rounded to 24 bits; RGBA exact"},
    {ExrCompression::b44, "b44", false, "lossy: RGBA in 4x4 blocks; Z exact, uncompressed"},
    {ExrCompression::b44a, "b44a", false, "lossy: as b44, flat blocks smaller"},
    {ExrCompression::dwaa, "dwaa", false, "lossy: RGB by DCT in 32 scanlines; A, Z exact"},
    {ExrCompression::dwab, "dwab", false, "lossy: as dwaa, 256 scanlines"},
}};

}  // namespace

std::span<const ExrCompressionInfo> exr_compressions() { return kCompressions; }

const ExrCompressionInfo& exr_compression_info(ExrCompression compression) {
  return kCompressions[static_cast<std::size_t>(compression)];
}

std::optional<ExrCompression> exr_compression_named(std::string_view name) {
  const auto* found = std::find_if(kCompressions.begin(), kCompressions.end(),
                                   [&](const ExrCompressionInfo& c) { return c.name == name; });
  if (found == kCompressions.end()) return std::nullopt;
  return found->compression;
}

}  // namespace tetray::render
