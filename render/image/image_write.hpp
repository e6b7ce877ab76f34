// Image files of docs/architecture.md §3, written atomically (temporary file in the same directory,
// then rename) so that a killed job never leaves a torn image.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "render/core/framebuffer.hpp"

namespace tetray::render {

struct WriteResult {
  bool ok = true;
  std::string message;  // what failed and where, when !ok
};

// EXR: channels R, G, B, A (half) and Z (float depth), scanline, ZIP compression.
WriteResult write_exr(const Framebuffer& image, const std::string& path);

// PNG: 8-bit sRGB RGBA. zlib level 0..9 (1 = fast, the default).
WriteResult write_png(const Framebuffer& image, const std::string& path, int compression_level = 1);

enum class ImageFormat { exr, png };

// The format named by the path's extension (.exr or .png, in any case); nullopt for others.
std::optional<ImageFormat> image_format_of(const std::string& path);

// write_exr or write_png by the path's extension; an error for any other extension.
WriteResult write_image(const Framebuffer& image, const std::string& path,
                        int png_compression_level = 1);

// Encoding apart from writing, so that a caller (the adaptor's writer thread) can run and time
// the two stages separately; write_exr and write_png are encode + write_file_atomically.
struct EncodedImage {
  std::vector<unsigned char> bytes;
  std::string error;  // empty on success

  bool ok() const { return error.empty(); }
};
EncodedImage encode_exr(const Framebuffer& image);
EncodedImage encode_png(const Framebuffer& image, int compression_level = 1);

// Writes `bytes` to a temporary file next to `path`, then renames it over `path`. On failure the
// temporary file is removed and an existing file at `path` is left as it was.
WriteResult write_file_atomically(const std::string& path, std::span<const unsigned char> bytes);

// The temporary file write_file_atomically names `<target>.tmp<pid>-<counter>`: only a process
// killed between creating and renaming it leaves one behind.
struct TemporaryName {
  std::string target;  // the file name it was to be renamed to
  long pid = 0;        // the process that created it
};
// The parts of such a file name; nullopt for any other name.
std::optional<TemporaryName> parse_temporary_name(const std::string& file_name);

// Removes the regular files directly in `directory` that are temporaries of write_file_atomically
// for a target name `is_target` accepts and whose creating process no longer exists on this
// machine; every other file is left alone. A missing directory has none.
WriteResult remove_stale_temporaries(const std::string& directory,
                                     const std::function<bool(const std::string&)>& is_target);

}  // namespace tetray::render
