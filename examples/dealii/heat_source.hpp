// The moving heat source: a Gaussian of peak SOURCE_PEAK circling the cube's vertical axis at
// height 0.4, once over the run. Used by the assembly and by the refinement before the first step.
#pragma once

#include <array>
#include <cmath>

inline constexpr double source_peak = 400.0;
inline constexpr double source_radius = 0.25;  // of the circle about the axis x = y = 0.5

inline std::array<double, 3> source_center(double time, double period) {
  const double angle = 2 * M_PI * time / period;
  return {0.5 + source_radius * std::cos(angle), 0.5 + source_radius * std::sin(angle), 0.4};
}

inline double source_value(const std::array<double, 3>& center, double width, double x, double y,
                           double z) {
  const double dx = x - center[0], dy = y - center[1], dz = z - center[2];
  return source_peak * std::exp(-(dx * dx + dy * dy + dz * dz) / (2 * width * width));
}
