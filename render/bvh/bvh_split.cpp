#include "render/bvh/bvh_split.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace tetray::render::build {

Box3 centroid_bounds(const BuildContext& ctx, std::uint32_t begin, std::uint32_t end) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::uint32_t>(begin, end, kParallelGrain), Box3{},
      [&](const auto& block, Box3 box) {
        for (std::uint32_t i = block.begin(); i < block.end(); ++i) box.grow(ctx.items[i].centroid);
        return box;
      },
      [](Box3 a, const Box3& b) {
        a.grow(b);
        return a;
      });
}

}  // namespace tetray::render::build
