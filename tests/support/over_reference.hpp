// The closed form of the "over" operator, the independent reference of the transparency tests:
// for layers listed front to back, colour = sum_i c_i a_i prod_{j<i} (1 - a_j) and
// alpha = 1 - prod_i (1 - a_i), in double. Written term by term, not as the renderer's running
// blend, so that a test does not check the code against itself.
#pragma once

#include <array>
#include <cstddef>
#include <span>

namespace tetray::testing {

// `Layer` has `color` (3 floats) and `alpha`.
template <typename Layer>
std::array<double, 4> over_front_to_back(std::span<const Layer> layers) {
  std::array<double, 4> out{};
  double clear = 1;  // prod_i (1 - a_i)
  for (std::size_t i = 0; i < layers.size(); ++i) {
    double seen = 1;  // prod_{j<i} (1 - a_j)
    for (std::size_t j = 0; j < i; ++j) seen *= 1.0 - layers[j].alpha;
    for (int c = 0; c < 3; ++c) out[c] += double{layers[i].color[c]} * layers[i].alpha * seen;
    clear *= 1.0 - layers[i].alpha;
  }
  out[3] = 1.0 - clear;
  return out;
}

}  // namespace tetray::testing
