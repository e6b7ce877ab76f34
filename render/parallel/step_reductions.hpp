// What the ranks of a render step combine, by name: the global ranges every rank needs (the
// adaptor agrees on them together with the step's outcome and the scenes some rank skips, in one
// allreduce), the log counters and peak memory the writer rank reduces, and the flags of what
// changed on any rank. Each travels as one flat array; pack and unpack are the only places that
// know its layout.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

#include "render/core/value_bounds.hpp"

namespace tetray::render {

struct SceneRanges {
  BoundingBox box;   // of the scene's volume: the automatic camera fit
  ValueRange color;  // of its color_by field: the automatic colormap range
  ValueRange cap;    // of its clip cap's field: the cap's automatic range
};

struct StepRanges {
  BoundingBox points;               // of every point: the origin all vertex stores share
  std::vector<SceneRanges> scenes;  // by scene index

  void clear();
};

std::vector<ValueRange> pack(const StepRanges& ranges);
// `ranges` must have the scene count of the packed value.
void unpack(std::span<const ValueRange> packed, StepRanges& ranges);

// Per scene, summed over the ranks for the timing log.
struct SceneCounters {
  std::uint64_t tets = 0;          // the solver's tets
  std::uint64_t kept_tets = 0;     // rendered: not ghost, not skipped
  std::uint64_t skipped_tets = 0;  // under nonfinite: skip_tets
  std::uint64_t bytes = 0;         // the renderer's copy and its BVH
};

std::vector<std::uint64_t> pack(std::span<const SceneCounters> counters);
void unpack(std::span<const std::uint64_t> packed, std::span<SceneCounters> counters);

// Collective: element-wise sums of the scenes' counters onto `root`, in place (the others' are
// left as they were). Returns MPI_SUCCESS or the MPI error code; no MPI traffic on one rank.
int sum_counters_to_root(std::span<SceneCounters> counters, int root, MPI_Comm comm);

// Collective: the maximum of `value` over the ranks onto `root`, in place, likewise.
int max_to_root(std::uint64_t& value, int root, MPI_Comm comm);

// Collective: each flag becomes the bitwise OR of its value on every rank, in one allreduce.
// Returns MPI_SUCCESS or the MPI error code.
int or_over_ranks(std::span<std::uint8_t> flags, MPI_Comm comm);

}  // namespace tetray::render
