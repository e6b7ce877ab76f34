#include "render/composite/composite.hpp"

#include <iterator>
#include <utility>

#include "render/composite/composite_codec.hpp"
#include "render/composite/compositor.hpp"

namespace tetray::render {
namespace {

bool well_formed(const Framebuffer& image) {
  const auto pixels = static_cast<std::int64_t>(image.width) * image.height;
  return image.width >= 0 && image.height >= 0 && pixels < (std::int64_t{1} << 31) &&
         image.depth.size() == static_cast<std::size_t>(pixels) &&
         image.hit.size() == image.depth.size() && image.rgba.size() == 4 * image.depth.size();
}

// Every rank must pass a well-formed image of the same size and the same options; checked in
// one small allreduce so that a mismatch returns an error everywhere instead of hanging.
int agree_on_inputs(const Framebuffer& image, MPI_Comm comm, const CompositeOptions& options,
                    int rank_count) {
  const bool image_ok = well_formed(image);
  const bool root_ok = options.root >= 0 && options.root < rank_count;
  const int width = image_ok ? image.width : 0;
  const int height = image_ok ? image.height : 0;
  const int root = root_ok ? options.root : 0;
  const int algorithm = static_cast<int>(options.algorithm);
  int maxima[] = {width, -width,    height,     -height,          root,
                  -root, algorithm, -algorithm, image_ok ? 0 : 1, root_ok ? 0 : 1};
  if (int error = MPI_Allreduce(MPI_IN_PLACE, maxima, static_cast<int>(std::size(maxima)), MPI_INT,
                                MPI_MAX, comm);
      error != MPI_SUCCESS) {
    return error;
  }
  if (maxima[9] != 0 || maxima[4] != -maxima[5]) return MPI_ERR_ROOT;
  const bool same = maxima[0] == -maxima[1] && maxima[2] == -maxima[3] && maxima[6] == -maxima[7];
  return same && maxima[8] == 0 ? MPI_SUCCESS : MPI_ERR_ARG;
}

}  // namespace

int composite(Framebuffer& image, MPI_Comm comm, const CompositeOptions& options,
              CompositeStats* stats) {
  CompositeStats local_stats;
  CompositeStats& out = stats ? *stats : local_stats;
  out = {};
  int rank = 0, rank_count = 1;
  if (int error = MPI_Comm_size(comm, &rank_count); error != MPI_SUCCESS) return error;
  if (rank_count == 1) return options.root == 0 ? MPI_SUCCESS : MPI_ERR_ROOT;
  const double start = MPI_Wtime();
  MPI_Comm_rank(comm, &rank);
  int error = agree_on_inputs(image, comm, options, rank_count);
  if (error == MPI_SUCCESS && image.pixel_count() > 0) {
    CompositePlan plan = make_plan(rank_count, options.algorithm);
    out.rounds = plan.round_count();
    error = Compositor<Framebuffer>(image, comm, rank, options.root, std::move(plan), out).run();
  }
  out.seconds = MPI_Wtime() - start;
  return error;
}

}  // namespace tetray::render
