// Text rasterized through FreeType: a font file opened once, strings turned into antialiased
// coverage masks at a pixel size. The adaptor opens the font when it reads its config, so that a
// missing or unreadable font is a config error, not a failure at some later step.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace tetray::render {

// DejaVu Sans as Debian's fonts-dejavu-core installs it.
inline constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Coverage of one line of text, 0..255 per pixel, row-major from the top-left. The pen starts at
// (pen_x, baseline); ink may reach left of the pen or below the baseline (descenders).
struct TextMask {
  int width = 0;
  int height = 0;
  int pen_x = 0;
  int baseline = 0;  // rows from the top of the mask to the baseline
  std::vector<std::uint8_t> coverage;

  std::uint8_t at(int x, int y) const { return coverage[static_cast<std::size_t>(y) * width + x]; }
};

class Font;

struct FontResult {
  std::shared_ptr<const Font> font;  // null on error
  std::string error;                 // names the file and what FreeType said
};

class Font {
 public:
  // Opens a TrueType/OpenType file (e.g. /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf).
  static FontResult open(const std::string& path);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  // The UTF-8 text as one line at `pixel_size` (the em height in pixels), with kerning. Invalid
  // UTF-8 bytes and code points the font lacks show the font's missing-glyph box. Thread-safe:
  // FreeType faces are not, so calls are serialised (text is a few dozen glyphs per image).
  TextMask rasterize(std::string_view utf8, int pixel_size) const;

  const std::string& path() const { return path_; }

 private:
  struct Handles;
  Font(std::string path, std::unique_ptr<Handles> handles);

  std::string path_;
  std::unique_ptr<Handles> handles_;
  mutable std::mutex mutex_;
};

// The code points of UTF-8 text; each malformed byte becomes U+FFFD.
std::vector<char32_t> decode_utf8(std::string_view text);

}  // namespace tetray::render
