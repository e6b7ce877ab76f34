// The check before compositing: every rank must pass a well-formed image of the same size, the
// same root and the same options, and have the room it needs. One small allreduce, so that a
// mismatch or a failed allocation on one rank returns an error on every rank instead of hanging
// the schedule. Both compositors (depth and fragments) ask it, each naming its own errors.
#pragma once

#include <mpi.h>

#include <cstdint>

#include "render/composite/composite.hpp"

namespace tetray::render {

// What one rank brings.
struct CompositeInputs {
  int width = 0, height = 0;
  bool image_ok = true;  // this rank's image is well formed
  int root = 0;
  int algorithm = 0;                  // the depth compositor's CompositeOptions::algorithm
  bool allocated = true;              // this rank's buffers for the composite could be allocated
  std::uint64_t largest_message = 0;  // in elements of one MPI count
  int row_order = 0;                  // the depth compositor's CompositeOptions::rows
  int active_rows = 0;                // rows from this rank's first active row to its last
};

// What every rank learns, the same on every rank.
struct CompositeAgreement {
  bool root_ok = true;          // every rank named the same root, within the ranks
  bool images_ok = true;        // every image well formed, all of one size
  bool same_algorithm = true;   // every rank asked for the same algorithm and row order
  bool allocated = true;        // on every rank
  bool counts_fit = true;       // every rank's largest message fits an int count
  int tallest_active_rows = 0;  // the most active_rows of any rank
};

// Collective over `comm` (of rank_count ranks); returns the allreduce's error code.
int agree_on(const CompositeInputs& mine, int rank_count, MPI_Comm comm,
             CompositeAgreement& agreement);

// The depth compositor's check: MPI_SUCCESS when every rank agrees; MPI_ERR_ROOT for a root out
// of range or not the same on every rank, MPI_ERR_ARG for a malformed image or differing sizes,
// algorithms or row orders; or the allreduce's error. Collective. `active_rows`: this rank's
// active rows (CompositeInputs); `tallest_active_rows` is set to the most of any rank.
int agree_on_inputs(int image_width, int image_height, bool image_ok, MPI_Comm comm,
                    const CompositeOptions& options, int rank_count, int active_rows,
                    int& tallest_active_rows);

}  // namespace tetray::render
