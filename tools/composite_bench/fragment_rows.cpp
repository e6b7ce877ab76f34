#include "tools/composite_bench/fragment_rows.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>

#include "render/composite/composite.hpp"
#include "render/composite/fragment_composite.hpp"

namespace tetray::composite_bench {
namespace {

// Two layers per hit of `image`: the surface at opacity 0.5 and another 0.1% of its depth behind.
render::FragmentImage two_layers(const render::Framebuffer& image) {
  render::FragmentImage out;
  out.width = image.width;
  out.height = image.height;
  out.begin.reserve(image.pixel_count() + 1);
  out.begin.push_back(0);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    if (image.hit[p] != render::kNoHit) {
      for (const float behind : {1.0f, 1.001f}) {
        render::Fragment f;
        f.depth_in = f.depth_out = image.depth[p] * behind;
        f.key = image.hit[p];
        for (int c = 0; c < 3; ++c) f.rgba[c] = 0.5f * image.rgba[4 * p + c];
        f.rgba[3] = 0.5f;
        out.fragments.push_back(f);
      }
    }
    out.begin.push_back(static_cast<std::uint32_t>(out.fragments.size()));
  }
  return out;
}

// The median over `repeat` runs of the slowest rank's time of `run` (collective); prepare(),
// untimed, comes before each: the copy of the image an opaque composite overwrites.
double median_ms(
    int repeat, MPI_Comm comm, const std::function<void()>& run,
    const std::function<void()>& prepare = [] {}) {
  std::vector<double> times;
  for (int k = 0; k < repeat; ++k) {
    prepare();
    MPI_Barrier(comm);
    double seconds = MPI_Wtime();
    run();
    seconds = MPI_Wtime() - seconds;
    MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, comm);
    times.push_back(1e3 * seconds);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace

std::vector<FragmentRow> measure_fragments(const std::vector<int>& sizes,
                                           const std::vector<Coverage>& coverages, int repeat,
                                           MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  std::vector<FragmentRow> rows;
  for (const int size : sizes) {
    for (const Coverage coverage : coverages) {
      const render::Framebuffer image = bench_image(coverage, size, rank, ranks);
      const render::FragmentImage layers = two_layers(image);
      const render::CompositeOptions opaque{render::CompositeAlgorithm::automatic, 0,
                                            footprint(coverage, size, rank, ranks)};
      render::CompositeWorkspace workspace;
      render::Framebuffer flat, blended;
      render::FragmentWorkspace<render::Fragment> kept;
      FragmentRow row;
      row.ranks = ranks;
      row.size = size;
      row.coverage = coverage_name(coverage);
      row.opaque_ms = median_ms(
          repeat, comm,
          [&] {
            if (render::composite(flat, comm, opaque, nullptr, &workspace) != MPI_SUCCESS)
              MPI_Abort(comm, 1);
          },
          [&] { flat = image; });
      row.fragments_ms = median_ms(repeat, comm, [&] {
        if (render::composite_fragments(layers, comm, 0, blended, {}, nullptr, &kept) !=
            MPI_SUCCESS)
          MPI_Abort(comm, 1);
      });
      row.fragments_per_rank = static_cast<double>(layers.fragments.size());
      MPI_Allreduce(MPI_IN_PLACE, &row.fragments_per_rank, 1, MPI_DOUBLE, MPI_MAX, comm);
      rows.push_back(row);
    }
  }
  return rows;
}

void print_fragment_rows(const std::vector<FragmentRow>& rows) {
  if (rows.empty()) return;
  std::printf(
      "\ntransparent (two layers per hit, fragments) against opaque compositing of the "
      "same image, automatic algorithm:\n");
  std::printf("%6s %6s %-7s %12s %12s %14s %8s %s\n", "ranks", "size", "mode", "opaque ms",
              "fragments ms", "fragments/rank", "ratio", "target");
  for (const FragmentRow& r : rows) {
    std::printf("%6d %6d %-7s %12.2f %12.2f %14.0f %7.1fx <= %.0fx: %s\n", r.ranks, r.size,
                r.coverage.c_str(), r.opaque_ms, r.fragments_ms, r.fragments_per_rank, r.ratio(),
                kFragmentTargetRatio, r.ratio() <= kFragmentTargetRatio ? "met" : "missed");
  }
}

}  // namespace tetray::composite_bench
