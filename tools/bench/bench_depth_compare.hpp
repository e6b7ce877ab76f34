// Per-pixel agreement of two depth images (+infinity = miss): an independent check that
// tetray's directly traced surface and the extracted triangles are the same surface.
#pragma once

#include <span>

namespace tetray::bench {

struct DepthAgreement {
  double agree_fraction = 0;   // pixels where both hit or both miss
  double median_rel_diff = 0;  // |a - b| / |b| over pixels both hit (0 when there are none)
};

DepthAgreement compare_depth(std::span<const float> tetray_depth,
                             std::span<const float> reference_depth);

}  // namespace tetray::bench
