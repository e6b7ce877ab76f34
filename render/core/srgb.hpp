// The sRGB transfer function (IEC 61966-2-1): the framebuffer is linear, published colormaps
// and PNG files are sRGB-encoded.
#pragma once

#include <cmath>

namespace tetray::render {

// Encoded sRGB value in [0, 1] to linear intensity.
inline double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace tetray::render
