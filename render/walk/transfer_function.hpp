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

  // True when the opacity is zero at every value in [lo, hi] as at() evaluates it: every
  // opacity point at() would interpolate between for such a value is zero, so a stretch whose
  // field stays in [lo, hi] lets all light through and emits nothing, exactly.
  bool clear_over(double lo, double hi) const;

  // The values where the color or the extinction changes slope, ascending: between two of
  // them both are linear in the value.
  std::vector<double> breakpoints() const;
};

// The transfer function sampled at its breakpoints, once per frame: where a stretch of a ray
// crosses a breakpoint the integral reads its sample here instead of evaluating the colormap and
// the ramp again (the same values: at() of the same breakpoint).
struct BreakpointTable {
  explicit BreakpointTable(const TransferFunction& tf);

  std::vector<double> values;                     // tf.breakpoints()
  std::vector<TransferFunction::Sample> samples;  // tf.at(values[k])
};

}  // namespace tetray::render
