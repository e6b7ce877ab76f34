#include "render/walk/fixed_step.hpp"

#include <cmath>

namespace tetray::render {

Gathered FixedStepSampler::stretch(double t_in, double t_out, double f_in, double f_out) {
  Gathered g;
  if (!(t_out > t_in)) return g;
  const double slope = (f_out - f_in) / (t_out - t_in);
  for (; next_ < t_out; next_ += step_) {
    const TransferFunction::Sample s = tf_.at(f_in + (next_ - t_in) * slope);
    const double alpha = 1 - std::exp(-s.extinction * step_);
    for (int c = 0; c < 3; ++c) g.color[c] += g.transmittance * alpha * s.color[c];
    g.transmittance *= 1 - alpha;
  }
  return g;
}

}  // namespace tetray::render
