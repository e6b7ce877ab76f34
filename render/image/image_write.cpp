// The image files of docs/architecture.md §3: encode in memory, then replace the file atomically.
#include "render/image/image_write.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace tetray::render {
namespace {

WriteResult write_encoded(const EncodedImage& encoded, const std::string& path) {
  if (!encoded.ok()) return {false, "cannot write '" + path + "': " + encoded.error};
  return write_file_atomically(path, encoded.bytes);
}

}  // namespace

WriteResult write_exr(const Framebuffer& image, const std::string& path) {
  return write_encoded(encode_exr(image), path);
}

WriteResult write_png(const Framebuffer& image, const std::string& path, int compression_level) {
  return write_encoded(encode_png(image, compression_level), path);
}

std::optional<ImageFormat> image_format_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".exr") return ImageFormat::exr;
  if (extension == ".png") return ImageFormat::png;
  return std::nullopt;
}

WriteResult write_image(const Framebuffer& image, const std::string& path,
                        int png_compression_level) {
  const std::optional<ImageFormat> format = image_format_of(path);
  if (!format) return {false, "cannot write '" + path + "': not an .exr or .png file name"};
  return *format == ImageFormat::exr ? write_exr(image, path)
                                     : write_png(image, path, png_compression_level);
}

}  // namespace tetray::render
