// The extract-then-trace reference on one time step of the in-situ loop, timed as a whole, so
// that the in-situ step ratio compares the two pipelines on the same step in the same seconds.
#pragma once

#include <cstdint>
#include <vector>

#include "bench_reference_embree.hpp"
#include "bench_reference_vtk.hpp"
#include "render/scene/camera.hpp"

namespace tetray::bench {

class ReferenceStep {
 public:
  // `packets`: trace in Embree's 16-ray packets, else in single rays (the faster at t = 0).
  // `tets` must outlive the reference (the contour's grid views it).
  ReferenceStep(const std::vector<std::int64_t>& tets, const render::Camera& camera, int threads,
                bool packets);

  // VTK contour + Embree new-step build + trace of the step's points and field. Not timed: handing
  // the contour's triangles to Embree's buffers, a copy a coupled pipeline would not make.
  double run_ms(const std::vector<double>& points, const std::vector<double>& field);

 private:
  Contour contour_;
  EmbreeReference embree_;
  bool packets_;
};

}  // namespace tetray::bench
