// Fixed-step sampling of the emission-absorption integral along the walk: the usual ray-casting
// quadrature (Max 1995, §4; Engel et al. 2006, §1.4), kept as the baseline that the exact
// per-tet integral (segment_integral.hpp) is measured against. Samples lie at equal distances
// h along the ray, from half a step past each entry into the domain; each takes the linear field
// of the tet that holds it and adds, front to back, C += T alpha c and T *= 1 - alpha with
// alpha = 1 - exp(-k h), k and c the transfer function's extinction and color at the sample.
#pragma once

#include "render/walk/segment_integral.hpp"
#include "render/walk/transfer_function.hpp"

namespace tetray::render {

class FixedStepSampler {
 public:
  FixedStepSampler(const TransferFunction& tf, double step) : tf_(tf), step_(step) {}

  // The ray enters the domain at t_entry: its first sample is half a step further.
  void restart(double t_entry) { next_ = t_entry + 0.5 * step_; }

  // The samples in [t_in, t_out), where the field goes linearly from f_in to f_out; stretches
  // come in order along the ray, each starting where the one before ended.
  Gathered stretch(double t_in, double t_out, double f_in, double f_out);

 private:
  const TransferFunction& tf_;
  double step_;
  double next_ = 0;  // the ray parameter of the next sample
};

}  // namespace tetray::render
