// Reads a PNG back with libpng's simplified API (tests only): 8-bit RGBA as stored in the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tetray::testing {

struct PngPixels {
  int width = 0;
  int height = 0;
  bool srgb = false;  // the file declares the sRGB color space
  std::vector<std::uint8_t> rgba;
  std::string error;  // empty on success
};

PngPixels read_png_rgba8(const std::string& path);

}  // namespace tetray::testing
