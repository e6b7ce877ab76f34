#include "render/walk/transfer_function.hpp"

#include <algorithm>

namespace tetray::render {

TransferFunction::Sample TransferFunction::at(double value) const {
  Sample s;
  const double span = range_hi - range_lo;
  const double u = span > 0 ? (value - range_lo) / span : 0.5;
  float rgb[3];
  colormap->lookup(static_cast<float>(std::clamp(u, 0.0, 1.0)), rgb);
  for (int c = 0; c < 3; ++c) s.color[c] = rgb[c];
  // The point at or before `value` and the next one; constant beyond the ends.
  const auto after = std::upper_bound(opacity.begin(), opacity.end(), value,
                                      [](double v, const OpacityPoint& p) { return v < p.value; });
  double o = after == opacity.begin() ? opacity.front().opacity : opacity.back().opacity;
  if (after != opacity.begin() && after != opacity.end()) {
    const OpacityPoint& a = after[-1];
    const OpacityPoint& b = after[0];
    o = a.opacity + (value - a.value) / (b.value - a.value) * (b.opacity - a.opacity);
  }
  s.extinction = o / unit_distance;
  return s;
}

BreakpointTable::BreakpointTable(const TransferFunction& tf) : values(tf.breakpoints()) {
  samples.reserve(values.size());
  for (const double v : values) samples.push_back(tf.at(v));
}

bool TransferFunction::clear_over(double lo, double hi) const {
  // at(v) reads the points before and after upper_bound(v), clamped to the ends.
  const auto after = [&](double v) {
    return std::upper_bound(opacity.begin(), opacity.end(), v,
                            [](double x, const OpacityPoint& p) { return x < p.value; });
  };
  auto first = after(lo);
  if (first != opacity.begin()) --first;
  auto last = after(hi);
  if (last == opacity.end()) --last;
  for (auto p = first; p <= last; ++p) {
    if (p->opacity != 0) return false;
  }
  return true;
}

std::vector<double> TransferFunction::breakpoints() const {
  std::vector<double> values;
  for (const OpacityPoint& p : opacity) values.push_back(p.value);
  const std::size_t stops = colormap->stops.size() / 3;
  for (std::size_t k = 0; k < stops && stops > 1; ++k) {
    values.push_back(range_lo + (range_hi - range_lo) * static_cast<double>(k) /
                                    static_cast<double>(stops - 1));
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

}  // namespace tetray::render
