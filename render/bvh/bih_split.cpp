// The BIH-style split (Wald et al. 2007, §5.1): a spatial median with no cost function, so the
// build is fast.
#include "render/bvh/bvh_split.hpp"

namespace tetray::render::build {
namespace {

constexpr int kMaxSpatialRetries = 32;

}  // namespace

// Halves the spatial interval along its longest axis; when every centroid falls on
// one side, keep halving that side's interval.
std::uint32_t split_bih(BuildContext& ctx, const Range& r, Range& left, Range& right) {
  Box3 box = r.box;
  for (int attempt = 0; attempt < kMaxSpatialRetries && r.depth < kObjectMedianDepth; ++attempt) {
    const int axis = box.longest_axis();
    const float mid = 0.5f * (box.lo[axis] + box.hi[axis]);
    const std::uint32_t m =
        partition_by(ctx, r, [&](const BuildItem& item) { return item.centroid[axis] < mid; });
    if (m != r.begin && m != r.end) {
      left = {r.begin, m, box, r.depth + 1};
      right = {m, r.end, box, r.depth + 1};
      left.box.hi[axis] = mid;
      right.box.lo[axis] = mid;
      return m;
    }
    (m == r.begin ? box.lo : box.hi)[axis] = mid;
  }
  return split_object_median(r, left, right);
}

}  // namespace tetray::render::build
