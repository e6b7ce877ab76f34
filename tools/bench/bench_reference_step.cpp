#include "bench_reference_step.hpp"

#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {

ReferenceStep::ReferenceStep(const std::vector<std::int64_t>& tets, const render::Camera& camera,
                             int threads, bool packets)
    : contour_(tets, kIsovalue),
      embree_(camera, threads, EmbreeBuild::new_step),
      packets_(packets) {}

double ReferenceStep::run_ms(const std::vector<double>& points, const std::vector<double>& field) {
  contour_.set_step(points, field);
  const double contour_ms = contour_.run_ms();
  const double build_ms = embree_.build_ms(contour_.triangles());
  return contour_ms + build_ms + embree_.trace_ms(packets_);
}

}  // namespace tetray::bench
