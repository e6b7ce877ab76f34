// Image files of DESIGN §3, written atomically (temporary file in the same directory, then
// rename) so that a killed job never leaves a torn image.
#pragma once

#include <string>

#include "render/framebuffer.hpp"

namespace tetray::render {

struct WriteResult {
  bool ok = true;
  std::string message;  // what failed and where, when !ok
};

// EXR: channels R, G, B, A (half) and Z (float depth), scanline, ZIP compression.
WriteResult write_exr(const Framebuffer& image, const std::string& path);

// PNG: 8-bit sRGB RGBA. zlib level 0..9 (1 = fast, the default).
WriteResult write_png(const Framebuffer& image, const std::string& path, int compression_level = 1);

}  // namespace tetray::render
