#include "font.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <climits>

namespace tetray::render {

struct Font::Handles {
  FT_Library library = nullptr;
  FT_Face face = nullptr;

  ~Handles() {
    if (face != nullptr) FT_Done_Face(face);
    if (library != nullptr) FT_Done_FreeType(library);
  }
};

namespace {

std::string freetype_error(FT_Error code) {
  const char* text = FT_Error_String(code);
  return text != nullptr ? text : "FreeType error " + std::to_string(code);
}

// One glyph's coverage and where it sits relative to the pen at the baseline.
struct PlacedGlyph {
  int x = 0, y = 0;  // top-left of the bitmap; y grows downwards, 0 on the baseline
  int width = 0, height = 0;
  std::vector<std::uint8_t> coverage;
};

PlacedGlyph copy_bitmap(const FT_GlyphSlot slot, int pen_x) {
  const FT_Bitmap& bitmap = slot->bitmap;
  PlacedGlyph g;
  g.x = pen_x + slot->bitmap_left;
  g.y = -slot->bitmap_top;
  g.width = static_cast<int>(bitmap.width);
  g.height = static_cast<int>(bitmap.rows);
  g.coverage.resize(static_cast<std::size_t>(g.width) * g.height);
  for (int row = 0; row < g.height; ++row) {
    const unsigned char* src = bitmap.buffer + static_cast<std::ptrdiff_t>(row) * bitmap.pitch;
    std::copy(src, src + g.width, g.coverage.begin() + static_cast<std::ptrdiff_t>(row) * g.width);
  }
  return g;
}

}  // namespace

std::vector<char32_t> decode_utf8(std::string_view text) {
  std::vector<char32_t> out;
  for (std::size_t k = 0; k < text.size();) {
    const auto lead = static_cast<unsigned char>(text[k]);
    const int extra = lead < 0x80         ? 0
                      : (lead >> 5) == 6  ? 1
                      : (lead >> 4) == 14 ? 2
                      : (lead >> 3) == 30 ? 3
                                          : -1;
    char32_t cp = extra == 0   ? lead
                  : extra == 1 ? lead & 0x1f
                  : extra == 2 ? lead & 0x0f
                               : lead & 7;
    bool valid = extra >= 0 && k + extra < text.size();
    for (int c = 1; valid && c <= extra; ++c) {
      const auto next = static_cast<unsigned char>(text[k + c]);
      valid = (next >> 6) == 2;
      cp = (cp << 6) | (next & 0x3f);
    }
    if (!valid) {
      out.push_back(U'\uFFFD');
      ++k;
      continue;
    }
    out.push_back(cp);
    k += 1 + extra;
  }
  return out;
}

Font::Font(std::string path, std::unique_ptr<Handles> handles)
    : path_(std::move(path)), handles_(std::move(handles)) {}

Font::~Font() = default;

FontResult Font::open(const std::string& path) {
  auto handles = std::make_unique<Handles>();
  if (FT_Error e = FT_Init_FreeType(&handles->library)) {
    return {nullptr, "cannot start FreeType: " + freetype_error(e)};
  }
  if (FT_Error e = FT_New_Face(handles->library, path.c_str(), 0, &handles->face)) {
    return {nullptr, "cannot open font '" + path + "': " + freetype_error(e)};
  }
  if (!FT_IS_SCALABLE(handles->face)) {
    return {nullptr, "font '" + path + "' is not scalable (give a TrueType or OpenType file)"};
  }
  return {std::shared_ptr<const Font>(new Font(path, std::move(handles))), {}};
}

TextMask Font::rasterize(std::string_view utf8, int pixel_size) const {
  std::lock_guard lock(mutex_);
  FT_Face face = handles_->face;
  TextMask mask;
  if (FT_Set_Pixel_Sizes(face, 0, static_cast<FT_UInt>(std::max(pixel_size, 1))) != 0) return mask;
  const int ascender = static_cast<int>(face->size->metrics.ascender >> 6);
  const int descender = static_cast<int>(face->size->metrics.descender >> 6);  // negative
  std::vector<PlacedGlyph> glyphs;
  long pen = 0;  // 26.6 fixed point
  FT_UInt previous = 0;
  for (char32_t cp : decode_utf8(utf8)) {
    const FT_UInt index = FT_Get_Char_Index(face, cp);
    if (previous != 0 && FT_HAS_KERNING(face)) {
      FT_Vector kern{};
      FT_Get_Kerning(face, previous, index, FT_KERNING_DEFAULT, &kern);
      pen += kern.x;
    }
    previous = index;
    if (FT_Load_Glyph(face, index, FT_LOAD_RENDER | FT_LOAD_TARGET_NORMAL) != 0) continue;
    glyphs.push_back(copy_bitmap(face->glyph, static_cast<int>(pen >> 6)));
    pen += face->glyph->advance.x;
  }
  // The mask spans the line box (ascender to descender, pen start to end) and all the ink.
  int left = 0, right = static_cast<int>((pen + 63) >> 6), top = -ascender, bottom = -descender;
  for (const PlacedGlyph& g : glyphs) {
    if (g.width == 0 || g.height == 0) continue;
    left = std::min(left, g.x);
    right = std::max(right, g.x + g.width);
    top = std::min(top, g.y);
    bottom = std::max(bottom, g.y + g.height);
  }
  mask.width = right - left;
  mask.height = bottom - top;
  mask.pen_x = -left;
  mask.baseline = -top;
  mask.coverage.assign(static_cast<std::size_t>(mask.width) * mask.height, 0);
  for (const PlacedGlyph& g : glyphs) {
    for (int row = 0; row < g.height; ++row) {
      for (int col = 0; col < g.width; ++col) {
        std::uint8_t& dst = mask.coverage[static_cast<std::size_t>(g.y - top + row) * mask.width +
                                          (g.x - left + col)];
        dst = std::max(dst, g.coverage[static_cast<std::size_t>(row) * g.width + col]);
      }
    }
  }
  return mask;
}

}  // namespace tetray::render
