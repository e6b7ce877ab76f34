#include "render/composite/composite_agreement.hpp"

#include <algorithm>
#include <climits>

namespace tetray::render {

int agree_on(const CompositeInputs& mine, int rank_count, MPI_Comm comm,
             CompositeAgreement& agreement) {
  const bool root_ok = mine.root >= 0 && mine.root < rank_count;
  const long long width = mine.image_ok ? mine.width : 0;
  const long long height = mine.image_ok ? mine.height : 0;
  const long long root = root_ok ? mine.root : 0;
  const long long largest =
      static_cast<long long>(std::min<std::uint64_t>(mine.largest_message, LLONG_MAX));
  // A value and its negation under MPI_MAX give the largest and the smallest: equal on every
  // rank exactly when both are the same. Flags are 1 where a rank failed.
  enum Slot {
    kWidth,
    kMinusWidth,
    kHeight,
    kMinusHeight,
    kRoot,
    kMinusRoot,
    kAlgorithm,
    kMinusAlgorithm,
    kRowOrder,
    kMinusRowOrder,
    kActiveRows,
    kBadImage,
    kBadRoot,
    kNotAllocated,
    kLargest,
    kSlots
  };
  long long maxima[kSlots] = {};
  maxima[kWidth] = width;
  maxima[kMinusWidth] = -width;
  maxima[kHeight] = height;
  maxima[kMinusHeight] = -height;
  maxima[kRoot] = root;
  maxima[kMinusRoot] = -root;
  maxima[kAlgorithm] = mine.algorithm;
  maxima[kMinusAlgorithm] = -mine.algorithm;
  maxima[kRowOrder] = mine.row_order;
  maxima[kMinusRowOrder] = -mine.row_order;
  maxima[kActiveRows] = mine.active_rows;
  maxima[kBadImage] = mine.image_ok ? 0 : 1;
  maxima[kBadRoot] = root_ok ? 0 : 1;
  maxima[kNotAllocated] = mine.allocated ? 0 : 1;
  maxima[kLargest] = largest;
  if (const int rc = MPI_Allreduce(MPI_IN_PLACE, maxima, kSlots, MPI_LONG_LONG, MPI_MAX, comm);
      rc != MPI_SUCCESS)
    return rc;
  const auto same = [&](Slot value, Slot minus) { return maxima[value] == -maxima[minus]; };
  agreement.root_ok = maxima[kBadRoot] == 0 && same(kRoot, kMinusRoot);
  agreement.images_ok =
      maxima[kBadImage] == 0 && same(kWidth, kMinusWidth) && same(kHeight, kMinusHeight);
  agreement.same_algorithm = same(kAlgorithm, kMinusAlgorithm) && same(kRowOrder, kMinusRowOrder);
  agreement.allocated = maxima[kNotAllocated] == 0;
  agreement.counts_fit = maxima[kLargest] <= INT_MAX;
  agreement.tallest_active_rows = static_cast<int>(maxima[kActiveRows]);
  return MPI_SUCCESS;
}

int agree_on_inputs(int image_width, int image_height, bool image_ok, MPI_Comm comm,
                    const CompositeOptions& options, int rank_count, int active_rows,
                    int& tallest_active_rows) {
  CompositeInputs mine;
  mine.width = image_width;
  mine.height = image_height;
  mine.image_ok = image_ok;
  mine.root = options.root;
  mine.algorithm = static_cast<int>(options.algorithm);
  mine.row_order = static_cast<int>(options.rows);
  mine.active_rows = active_rows;
  CompositeAgreement agreed;
  if (const int rc = agree_on(mine, rank_count, comm, agreed); rc != MPI_SUCCESS) return rc;
  if (!agreed.root_ok) return MPI_ERR_ROOT;
  tallest_active_rows = agreed.tallest_active_rows;
  return agreed.images_ok && agreed.same_algorithm ? MPI_SUCCESS : MPI_ERR_ARG;
}

}  // namespace tetray::render
