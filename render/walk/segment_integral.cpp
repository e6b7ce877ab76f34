#include "render/walk/segment_integral.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::render {
namespace {

// 4-point Gauss-Legendre on [0, 1].
constexpr double kNode[4] = {0.0694318442029737, 0.330009478207572, 0.669990521792428,
                             0.930568155797026};
constexpr double kWeight[4] = {0.173927422568727, 0.326072577431273, 0.326072577431273,
                               0.173927422568727};
constexpr double kSubpieceDepth = 0.25;

// One piece on which color and extinction go linearly from a to b over `length`.
Gathered integrate_piece(const TransferFunction::Sample& a, const TransferFunction::Sample& b,
                         double length) {
  Gathered g;
  const double k0 = a.extinction, dk = b.extinction - a.extinction;
  const double depth = 0.5 * (a.extinction + b.extinction) * length;
  g.transmittance = std::exp(-depth);
  if (!(depth > 0)) return g;
  // Optical depth from the piece's start to u in [0, 1]: (k0 u + dk u^2 / 2) length.
  const auto depth_at = [&](double u) { return (k0 * u + 0.5 * dk * u * u) * length; };
  const int subpieces = std::max(1, static_cast<int>(std::ceil(depth / kSubpieceDepth)));
  for (int s = 0; s < subpieces; ++s) {
    for (int q = 0; q < 4; ++q) {
      const double u = (s + kNode[q]) / subpieces;
      const double w = kWeight[q] / subpieces * length * (k0 + dk * u) * std::exp(-depth_at(u));
      for (int c = 0; c < 3; ++c) g.color[c] += w * (a.color[c] + u * (b.color[c] - a.color[c]));
    }
  }
  return g;
}

}  // namespace

Gathered integrate_segment(const TransferFunction& tf, const BreakpointTable& table, double length,
                           double f_in, double f_out) {
  Gathered total;
  if (!(length > 0)) return total;
  const double lo = std::min(f_in, f_out), hi = std::max(f_in, f_out);
  // Empty space: every piece below would let all light through and add no color.
  if (tf.clear_over(lo, hi)) return total;
  // The breakpoints strictly inside (lo, hi), in the order the ray meets them.
  const std::vector<double>& values = table.values;
  const auto first = std::upper_bound(values.begin(), values.end(), lo) - values.begin();
  const auto last = std::lower_bound(values.begin(), values.end(), hi) - values.begin();
  double u0 = 0;
  TransferFunction::Sample s0 = tf.at(f_in);
  const auto piece_to = [&](double u1, const TransferFunction::Sample& s1) {
    total.then(integrate_piece(s0, s1, (u1 - u0) * length));
    u0 = u1;
    s0 = s1;
  };
  const std::ptrdiff_t count = last - first;
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto at = static_cast<std::size_t>(f_out > f_in ? first + k : last - 1 - k);
    piece_to((values[at] - f_in) / (f_out - f_in), table.samples[at]);
  }
  piece_to(1.0, tf.at(f_out));
  return total;
}

}  // namespace tetray::render
