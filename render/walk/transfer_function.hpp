// The transfer function of a volume scene: a colormap over a value range and an opacity ramp of
// [value, opacity] points, both piecewise linear in the value (constant beyond their ends). An
// opacity o is an extinction of o / unit_distance per unit length, so a slab of thickness
// unit_distance at opacity o has optical depth o (ParaView's "scalar opacity unit distance").
// Emission is the color times the extinction (the emission-absorption model, Max 1995, §4).
#pragma once

#include <array>
#include <vector>

#include "render/scene/colormap.hpp"

namespace tetray::render {

struct OpacityPoint {
  double value = 0;
  double opacity = 0;  // >= 0
};

struct TransferFunction {
  const Colormap* colormap = nullptr;
  double range_lo = 0, range_hi = 1;  // the colormap spans [range_lo, range_hi]
  std::vector<OpacityPoint> opacity;  // ascending values, at least one
  double unit_distance = 1;           // > 0

  struct Sample {
    std::array<double, 3> color{};  // linear RGB
    double extinction = 0;          // per unit length
  };
  Sample at(double value) const;

  // The values where the color or the extinction changes slope, ascending: between two of
  // them both are linear in the value.
  std::vector<double> breakpoints() const;
};

}  // namespace tetray::render
