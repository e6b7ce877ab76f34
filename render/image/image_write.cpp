// The image files of docs/architecture.md §3: encode in memory, then replace the file atomically.
#include "render/image/image_write.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <tbb/parallel_invoke.h>

namespace tetray::render {
namespace {

WriteResult write_encoded(const EncodedImage& encoded, const std::string& path) {
  if (!encoded.ok()) return {false, "cannot write '" + path + "': " + encoded.error};
  return write_file_atomically(path, encoded.bytes);
}

}  // namespace

WriteResult write_exr(const Framebuffer& image, const std::string& path,
                      ExrCompression compression) {
  return write_encoded(encode_exr(image, compression), path);
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

EncodedImage encode_image(ImageFormat format, const Framebuffer& image,
                          const EncodeOptions& options) {
  return format == ImageFormat::exr ? encode_exr(image, options.exr_compression)
                                    : encode_png(image, options.png_compression);
}

EncodedImages encode_images(const Framebuffer& image, bool exr, bool png,
                            const EncodeOptions& options) {
  EncodedImages encoded;
  const auto encode_exr_image = [&] {
    if (exr) encoded.exr = encode_image(ImageFormat::exr, image, options);
  };
  const auto encode_png_image = [&] {
    if (png) encoded.png = encode_image(ImageFormat::png, image, options);
  };
  tbb::parallel_invoke(encode_exr_image, encode_png_image);
  return encoded;
}

WriteResult write_image(const Framebuffer& image, const std::string& path,
                        const EncodeOptions& options) {
  const std::optional<ImageFormat> format = image_format_of(path);
  if (!format) return {false, "cannot write '" + path + "': not an .exr or .png file name"};
  return write_encoded(encode_image(*format, image, options), path);
}

}  // namespace tetray::render
