#include "bench_trace_in_turn.hpp"

#include <array>
#include <functional>

#include "bench_reference_embree.hpp"
#include "bench_timing.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {

// More rounds than the other figures take: the trace targets are ratios of two frames of tens
// of milliseconds, and each extra round costs two frames.
constexpr int kTraceRounds = 7;

TraceInTurn trace_in_turn(const GyroidTwist& scene, const TriangleSoup& triangles,
                          const render::Camera& camera, int threads, bool packets) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  EmbreeReference embree(camera, threads);
  embree.build_ms(triangles);
  render::Framebuffer image;
  const auto tetray_ms = [&] {
    return time_ms([&] { trace_scene(volume, bvh, camera, render::TraceOptions{}.packet, image); });
  };
  const auto embree_ms = [&] { return embree.trace_ms(packets); };
  tetray_ms();  // warm-ups
  embree_ms();
  const std::array<double, 2> best = best_in_turn_ms<2>(kTraceRounds, {tetray_ms, embree_ms});
  return {kTraceRounds, best[0], best[1]};
}

}  // namespace tetray::bench
