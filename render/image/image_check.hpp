// The shape check every image encoder runs before touching a framebuffer's arrays.
#pragma once

#include <string>

#include "render/core/framebuffer.hpp"

namespace tetray::render {

// Empty when the framebuffer is non-empty and its arrays match its size; otherwise what is wrong.
inline std::string framebuffer_problem(const Framebuffer& image) {
  if (image.width <= 0 || image.height <= 0) {
    return "empty image (" + std::to_string(image.width) + "x" + std::to_string(image.height) + ")";
  }
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  if (image.rgba.size() != 4 * pixels || image.depth.size() != pixels) {
    return "framebuffer arrays do not match its size " + std::to_string(image.width) + "x" +
           std::to_string(image.height);
  }
  return {};
}

}  // namespace tetray::render
