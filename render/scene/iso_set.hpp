// The isovalues of a frame, sorted, and the sign rule's crossing test against a value range
// (docs/architecture.md §3: a value at or above the isovalue counts as above), for one range (a BVH
// node's) or a batch of ranges (a leaf's tets).
#pragma once

#include "render/core/simd.hpp"

namespace tetray::render {

inline constexpr int kMaxIsovalues = 16;

struct IsoSet {
  float values[kMaxIsovalues];
  int count = 0;

  // Some isovalue lies in (fmin, fmax]: some vertex below it and some at or above.
  bool straddled_by(float fmin, float fmax) const {
    for (int k = 0; k < count; ++k) {
      if (values[k] > fmax) return false;
      if (values[k] > fmin) return true;
    }
    return false;
  }

  // The same for each lane.
  simd::Mask straddled_by(simd::Floats fmin, simd::Floats fmax) const {
    simd::Mask any(false);
    for (int k = 0; k < count; ++k) {
      const simd::Floats value(values[k]);
      any = any | ((fmin < value) & (value <= fmax));
    }
    return any;
  }
};

}  // namespace tetray::render
