#include "bench_depth_compare.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace tetray::bench {

DepthAgreement compare_depth(std::span<const float> tetray_depth,
                             std::span<const float> reference_depth) {
  if (tetray_depth.size() != reference_depth.size())
    throw std::invalid_argument("depth images differ in size");
  std::size_t agree = 0;
  std::vector<double> rel_diffs;
  for (std::size_t p = 0; p < tetray_depth.size(); ++p) {
    const bool hit_a = std::isfinite(tetray_depth[p]);
    const bool hit_b = std::isfinite(reference_depth[p]);
    agree += hit_a == hit_b;
    if (hit_a && hit_b)
      rel_diffs.push_back(std::abs(double{tetray_depth[p]} - reference_depth[p]) /
                          std::abs(double{reference_depth[p]}));
  }
  DepthAgreement result;
  result.agree_fraction =
      tetray_depth.empty() ? 1.0
                           : static_cast<double>(agree) / static_cast<double>(tetray_depth.size());
  if (!rel_diffs.empty()) {
    const auto middle = rel_diffs.begin() + static_cast<std::ptrdiff_t>(rel_diffs.size() / 2);
    std::nth_element(rel_diffs.begin(), middle, rel_diffs.end());
    result.median_rel_diff = *middle;
  }
  return result;
}

}  // namespace tetray::bench
