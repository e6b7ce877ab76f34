// The scanline EXR files tetray assembles itself (OpenEXR 3.1's file layout, the OpenEXR
// documentation's "OpenEXR File Layout"), for the lossless compressions the writer uses every
// step: none, RLE, ZIPS and ZIP. OpenEXR's own OutputFile spends most of its time copying the
// frame buffer through its generic slices and in its byte-at-a-time RLE (README, "Encoding");
// here the line blocks are built straight from the framebuffer, the halves converted four at a
// time (SSE2), RLE scanned 16 bytes at a time and ZIP's zlib stream compressed by libdeflate. The
// files are the same format as OpenEXR's (same header attributes, channels and line blocks),
// read by any OpenEXR reader; the other compressions go through OpenEXR (exr_encode.cpp).
#pragma once

#include <vector>

#include "render/core/framebuffer.hpp"
#include "render/image/image_write.hpp"

namespace tetray::render {

// Whether encode_exr_scanlines writes `compression`.
bool exr_scanlines_write(ExrCompression compression);

// The whole file into `bytes`: channels A, B, G, R (half) and Z (float), increasing y. The
// framebuffer's shape is checked by the caller; the bytes do not depend on the thread count.
void encode_exr_scanlines(const Framebuffer& image, ExrCompression compression,
                          std::vector<unsigned char>& bytes);

}  // namespace tetray::render
