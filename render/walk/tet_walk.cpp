#include "render/walk/tet_walk.hpp"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_reduce.h>

#include <limits>

namespace tetray::render {

template <typename Layout>
std::vector<WalkSegment> walk_segments(const WalkMesh<Layout>& mesh, const RayFrame& frame,
                                       double t_max, std::size_t max_segments,
                                       WalkCounters& counters) {
  std::vector<WalkSegment> segments;
  walk_ray(
      mesh, frame, t_max,
      [&](const WalkSegment& s) {
        segments.push_back(s);
        return segments.size() < max_segments;
      },
      counters);
  return segments;
}

template <typename Layout>
WalkCounters walk_rays(const WalkMesh<Layout>& mesh, Vec3d eye, std::span<const Vec3d> directions) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, directions.size(), 64), WalkCounters{},
      [&](const tbb::blocked_range<std::size_t>& r, WalkCounters counters) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          walk_ray(
              mesh, RayFrame(eye, directions[i]), std::numeric_limits<double>::infinity(),
              [](const WalkSegment&) { return true; }, counters);
        }
        return counters;
      },
      [](WalkCounters a, const WalkCounters& b) { return a += b; });
}

template WalkCounters walk_rays<Tet20>(const WalkMesh<Tet20>&, Vec3d, std::span<const Vec3d>);
template WalkCounters walk_rays<Tet16>(const WalkMesh<Tet16>&, Vec3d, std::span<const Vec3d>);

template std::vector<WalkSegment> walk_segments<Tet20>(const WalkMesh<Tet20>&, const RayFrame&,
                                                       double, std::size_t, WalkCounters&);
template std::vector<WalkSegment> walk_segments<Tet16>(const WalkMesh<Tet16>&, const RayFrame&,
                                                       double, std::size_t, WalkCounters&);

}  // namespace tetray::render
