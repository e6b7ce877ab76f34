#include "render/composite/composite_agreement.hpp"

#include <iterator>

namespace tetray::render {

int agree_on_inputs(int image_width, int image_height, bool image_ok, MPI_Comm comm,
                    const CompositeOptions& options, int rank_count) {
  const bool root_ok = options.root >= 0 && options.root < rank_count;
  const int width = image_ok ? image_width : 0;
  const int height = image_ok ? image_height : 0;
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

}  // namespace tetray::render
