// Emission-absorption along one tet's stretch of a ray (docs/architecture.md §8). The field is
// linear along the stretch, so cutting it where the field crosses a transfer-function
// breakpoint leaves pieces on which the color c and the extinction k are linear in t. A piece
// of length l then emits C = int_0^l c(t) k(t) exp(-int_0^t k) dt and lets T = exp(-(k0 + k1) l/2)
// through, exactly; the smooth 1D integral C is done by 4-point Gauss-Legendre on sub-pieces of
// optical depth at most 1/4, within 1e-9 relative of the closed form (which needs erf of real or
// imaginary arguments, Williams and Max 1992, and cancels badly on thin pieces).
#pragma once

#include <array>
#include <span>

#include "render/walk/transfer_function.hpp"

namespace tetray::render {

// Light gathered along a stretch, front to back: premultiplied color and the transmittance.
struct Gathered {
  std::array<double, 3> color{};
  double transmittance = 1;

  // This stretch followed by `behind`.
  void then(const Gathered& behind) {
    for (int c = 0; c < 3; ++c) color[c] += transmittance * behind.color[c];
    transmittance *= behind.transmittance;
  }
};

// The stretch of length `length` along which the field goes linearly from f_in to f_out;
// `breakpoints` is tf.breakpoints().
Gathered integrate_segment(const TransferFunction& tf, std::span<const double> breakpoints,
                           double length, double f_in, double f_out);

}  // namespace tetray::render
