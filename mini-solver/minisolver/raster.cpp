#include "minisolver/raster.hpp"

#include <png.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace minisolver {
namespace {

// 3x5 glyphs, five rows of three bits, top row first, left pixel the high bit.
std::uint16_t glyph(char c) {
  static constexpr std::uint16_t kDigits[10] = {
      0b111'101'101'101'111, 0b010'110'010'010'111, 0b111'001'111'100'111, 0b111'001'111'001'111,
      0b101'101'111'001'001, 0b111'100'111'001'111, 0b111'100'111'101'111, 0b111'001'001'001'001,
      0b111'101'111'101'111, 0b111'101'111'001'111};
  static constexpr std::uint16_t kLetters[26] = {
      0b010'101'111'101'101, 0b110'101'110'101'110, 0b011'100'100'100'011, 0b110'101'101'101'110,
      0b111'100'110'100'111, 0b111'100'110'100'100, 0b011'100'101'101'011, 0b101'101'111'101'101,
      0b111'010'010'010'111, 0b001'001'001'101'010, 0b101'101'110'101'101, 0b100'100'100'100'111,
      0b101'111'111'101'101, 0b110'101'101'101'101, 0b010'101'101'101'010, 0b110'101'110'100'100,
      0b010'101'101'110'011, 0b110'101'110'101'101, 0b011'100'010'001'110, 0b111'010'010'010'010,
      0b101'101'101'101'111, 0b101'101'101'101'010, 0b101'101'111'111'101, 0b101'101'010'101'101,
      0b101'101'010'010'010, 0b111'001'010'100'111};
  const unsigned char u = static_cast<unsigned char>(std::toupper(static_cast<unsigned char>(c)));
  if (u >= '0' && u <= '9') return kDigits[u - '0'];
  if (u >= 'A' && u <= 'Z') return kLetters[u - 'A'];
  if (u == '-') return 0b000'000'111'000'000;
  if (u == '.') return 0b000'000'000'000'010;
  if (u == '_') return 0b000'000'000'000'111;
  return 0;
}

}  // namespace

Raster::Raster(int width, int height, Rgb background)
    : width_(width), height_(height), pixels_(3 * static_cast<std::size_t>(width) * height) {
  fill_rect(0, 0, width - 1, height - 1, background);
}

Rgb Raster::at(int x, int y) const {
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * width_ + x);
  return {pixels_[i], pixels_[i + 1], pixels_[i + 2]};
}

void Raster::set(int x, int y, Rgb color) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * width_ + x);
  for (int k = 0; k < 3; ++k) pixels_[i + k] = color[k];
}

void Raster::fill_rect(int x0, int y0, int x1, int y1, Rgb color) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) set(x, y, color);
}

void Raster::line(int x0, int y0, int x1, int y1, Rgb color, int thickness) {
  // Bresenham; a thick line is a square brush along it.
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  const int half = thickness / 2;
  for (int err = dx + dy;;) {
    fill_rect(x0 - half, y0 - half, x0 - half + thickness - 1, y0 - half + thickness - 1, color);
    if (x0 == x1 && y0 == y1) return;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

int Raster::text(int x, int y, const std::string& s, Rgb color, int scale) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::uint16_t bits = glyph(s[i]);
    const int left = x + static_cast<int>(i) * 4 * scale;
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (bits & (1 << (14 - 3 * row - col)))
          fill_rect(left + col * scale, y + row * scale, left + (col + 1) * scale - 1,
                    y + (row + 1) * scale - 1, color);
  }
  return text_width(s, scale);
}

int Raster::text_width(const std::string& s, int scale) {
  return s.empty() ? 0 : (4 * static_cast<int>(s.size()) - 1) * scale;
}

namespace {

// Writes 8-bit RGB rows with libpng, which reports errors by longjmp back to the setjmp here:
// this frame holds nothing a longjmp could leave half-made (C++ objects built after setjmp
// returned a second time would be; GCC warns of them at -O1).
bool write_rgb_png(std::FILE* file, int width, int height, const std::uint8_t* rgb) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y)
    png_write_row(png, rgb + 3 * static_cast<std::size_t>(y) * width);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

bool Raster::write_png(const std::string& path, std::string& error) const {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"),
                                                             &std::fclose);
  if (!file) {
    error = "cannot open " + path + " for writing";
    return false;
  }
  if (!write_rgb_png(file.get(), width_, height_, pixels_.data())) {
    error = "libpng failed writing " + path;
    return false;
  }
  return true;
}

}  // namespace minisolver
