#include "support/png_read.hpp"

#include <png.h>

namespace tetray::testing {

PngPixels read_png_rgba8(const std::string& path) {
  PngPixels out;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    out.error = image.message;
    return out;
  }
  out.srgb = (image.flags & PNG_IMAGE_FLAG_COLORSPACE_NOT_sRGB) == 0;
  image.format = PNG_FORMAT_RGBA;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgba.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr)) {
    out.error = image.message;
    out.rgba.clear();
  }
  return out;
}

}  // namespace tetray::testing
