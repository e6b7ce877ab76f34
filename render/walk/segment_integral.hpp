// Emission-absorption along one tet's stretch of a ray (Max 1995; docs/architecture.md §8):
// emission = color x extinction, extinction = opacity / unit_distance, both piecewise linear in
// the value. The field is linear along the stretch, so cutting it where the field crosses a
// transfer-function breakpoint leaves pieces on which the color c and the extinction k are linear
// in t. A piece of length l then emits C = int_0^l c(t) k(t) exp(-int_0^t k) dt and lets
// T = exp(-(k0 + k1) l/2) through, exactly; the smooth 1D integral C is done by 4-point
// Gauss-Legendre on sub-pieces of optical depth at most 1/4, within 1e-9 relative.
// Why not the closed form: it needs erf of real or imaginary arguments (Williams and Max 1992) and
// cancels catastrophically on thin pieces, which a walk produces by the million. Why not
// pre-integration (Engel et al. 2001): a 2D table per transfer function approximates in the value
// and must be rebuilt whenever the automatic range moves, at every step. Why not sampling: its
// error depends on a step size the user must choose; tetray-bench --dvr-study measures what the
// exact integration costs instead.
#pragma once

#include <array>

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
// `table` is tf's.
Gathered integrate_segment(const TransferFunction& tf, const BreakpointTable& table, double length,
                           double f_in, double f_out);

}  // namespace tetray::render
