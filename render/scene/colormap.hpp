// Colormaps for coloring a surface by a field: piecewise-linear in RGB between stops.
#pragma once

#include <string_view>
#include <vector>

namespace tetray::render {

struct Rgb;

struct Colormap {
  std::vector<float> stops;  // r, g, b triplets, evenly spaced over [0, 1]

  // Color at s in [0, 1] (clamped).
  void lookup(float s, float rgb[3]) const;
};

// "viridis", "coolwarm" or "grayscale"; nullptr for an unknown name.
const Colormap* find_colormap(std::string_view name);

}  // namespace tetray::render
