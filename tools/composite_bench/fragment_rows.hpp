// Transparent compositing against opaque compositing of the same image: each rank's bench image
// (bench_images.hpp) also as two zero-length fragments per hit (two surfaces at opacity 0.5, one
// just behind the other, as a transparent scene's layers), composited by the fragment compositor
// as the adaptor composites a transparent scene (render/composite/fragment_composite.hpp, the
// writer's merged fragments kept between runs), beside render::composite of the image. The
// in-situ budget's target: fragments at most twice the opaque time.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

#include "tools/composite_bench/bench_images.hpp"

namespace tetray::composite_bench {

inline constexpr double kFragmentTargetRatio = 2.0;

struct FragmentRow {
  int ranks = 0, size = 0;
  std::string coverage;
  double opaque_ms = 0, fragments_ms = 0;  // medians of the slowest rank's time per run
  double fragments_per_rank = 0;           // the largest count any rank sends

  double ratio() const { return opaque_ms > 0 ? fragments_ms / opaque_ms : 0; }
};

// Collective over `comm`: a row per size and coverage.
std::vector<FragmentRow> measure_fragments(const std::vector<int>& sizes,
                                           const std::vector<Coverage>& coverages, int repeat,
                                           MPI_Comm comm);

void print_fragment_rows(const std::vector<FragmentRow>& rows);

}  // namespace tetray::composite_bench
