// An RGB raster with the few drawing operations the plots need, and its PNG writer.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace minisolver {

using Rgb = std::array<std::uint8_t, 3>;

class Raster {
 public:
  Raster(int width, int height, Rgb background);

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const;
  void set(int x, int y, Rgb color);                          // ignores pixels outside
  void fill_rect(int x0, int y0, int x1, int y1, Rgb color);  // inclusive corners
  void line(int x0, int y0, int x1, int y1, Rgb color, int thickness = 1);
  // Upper-left corner at (x, y); each font pixel becomes scale x scale. Returns the text width.
  int text(int x, int y, const std::string& s, Rgb color, int scale = 2);
  static int text_width(const std::string& s, int scale = 2);

  bool write_png(const std::string& path, std::string& error) const;

 private:
  int width_, height_;
  std::vector<std::uint8_t> pixels_;  // RGB rows, top first
};

}  // namespace minisolver
