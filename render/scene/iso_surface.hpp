// An isosurface of a scene: its isovalue, color and opacity, as trace draws it and as the walk
// meets it along a ray (render/walk/surface_crossing.hpp).
#pragma once

namespace tetray::render {

struct Rgb {
  float r = 1, g = 1, b = 1;
};

struct IsoSurface {
  float value = 0;
  Rgb color{};
  float opacity = 1;  // below 1: transparent, drawn by trace_layers
};

}  // namespace tetray::render
