#include "render/walk/tet_walk.hpp"

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

template std::vector<WalkSegment> walk_segments<Tet20>(const WalkMesh<Tet20>&, const RayFrame&,
                                                       double, std::size_t, WalkCounters&);
template std::vector<WalkSegment> walk_segments<Tet16>(const WalkMesh<Tet16>&, const RayFrame&,
                                                       double, std::size_t, WalkCounters&);

}  // namespace tetray::render
