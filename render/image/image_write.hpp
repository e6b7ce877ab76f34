// Image files of docs/architecture.md §3, written atomically (temporary file in the same directory,
// then rename) so that a killed job never leaves a torn image.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/core/framebuffer.hpp"

namespace tetray::render {

struct WriteResult {
  bool ok = true;
  std::string message;  // what failed and where, when !ok
};

// The compressions of OpenEXR 3.1, numbered as its Imf::Compression.
enum class ExrCompression { none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab };

struct ExrCompressionInfo {
  ExrCompression compression;
  std::string_view name;  // lower case, as the config spells it: "zip", "piz", ...
  bool lossless;          // for both channel types of the image (RGBA half, Z float)
  std::string_view what;  // one line: how it works, what it loses
};
std::span<const ExrCompressionInfo> exr_compressions();  // all, in enum order
const ExrCompressionInfo& exr_compression_info(ExrCompression compression);
std::optional<ExrCompression> exr_compression_named(std::string_view name);

// The PNG deflate levels (libdeflate's scale: 0 stores, 1 fastest, 12 smallest).
inline constexpr int kMaxPngCompression = 12;

// How the writer encodes; the defaults are the config's (docs/architecture.md §3, §4).
struct EncodeOptions {
  ExrCompression exr_compression = ExrCompression::rle;
  int png_compression = 1;
};

// EXR: channels R, G, B, A (half) and Z (float depth), scanline.
WriteResult write_exr(const Framebuffer& image, const std::string& path,
                      ExrCompression compression = EncodeOptions{}.exr_compression);

// PNG: 8-bit sRGB RGBA at a deflate level 0..kMaxPngCompression.
WriteResult write_png(const Framebuffer& image, const std::string& path,
                      int compression_level = EncodeOptions{}.png_compression);

enum class ImageFormat { exr, png };

// The format named by the path's extension (.exr or .png, in any case); nullopt for others.
std::optional<ImageFormat> image_format_of(const std::string& path);

// write_exr or write_png by the path's extension; an error for any other extension.
WriteResult write_image(const Framebuffer& image, const std::string& path,
                        const EncodeOptions& options = {});

// Encoding apart from writing, so that a caller (the adaptor's writer thread) can run and time
// the two stages separately; write_exr and write_png are encode + write_file_atomically.
struct EncodedImage {
  std::vector<unsigned char> bytes;
  std::string error;  // empty on success

  bool ok() const { return error.empty(); }
};
// Both run their loops with oneTBB in the caller's arena.
EncodedImage encode_exr(const Framebuffer& image,
                        ExrCompression compression = EncodeOptions{}.exr_compression);
EncodedImage encode_png(const Framebuffer& image,
                        int compression_level = EncodeOptions{}.png_compression);
EncodedImage encode_image(ImageFormat format, const Framebuffer& image,
                          const EncodeOptions& options);
// The EXR and the PNG of one image, as tasks of the caller's arena that run at once where both
// are wanted; a format not wanted stays empty.
struct EncodedImages {
  EncodedImage exr, png;
};
EncodedImages encode_images(const Framebuffer& image, bool exr, bool png,
                            const EncodeOptions& options);

// Writes `bytes` to a temporary file next to `path`, then renames it over `path`. On failure the
// temporary file is removed and an existing file at `path` is left as it was.
WriteResult write_file_atomically(const std::string& path, std::span<const unsigned char> bytes);

// A new, empty temporary file next to `path`, named as write_file_atomically names its own, for
// a writer that fills it over time and renames it over `path` once whole (the movie). Returns
// its name, or empty with `error` set.
std::string create_temporary_file(const std::string& path, std::string& error);

// The temporary file write_file_atomically (and create_temporary_file) names
// `<target>.tmp<pid>-<counter>`: only a process killed between creating and renaming it leaves
// one behind.
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
