// What the ranks of a render step combine, by name: the global ranges every rank needs and the
// scenes some rank skips (agreed together with the step's outcome, in one allreduce:
// collective.hpp) and the log counters the writer rank sums. Each travels as one flat array;
// pack and unpack are the only places that know its layout.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "render/core/value_bounds.hpp"

namespace tetray {

struct SceneRanges {
  render::BoundingBox box;   // of the scene's volume: the automatic camera fit
  render::ValueRange color;  // of its color_by field: the automatic colormap range
  render::ValueRange cap;    // of its clip cap's field: the cap's automatic range
};

struct StepRanges {
  render::BoundingBox points;       // of every point: the origin all vertex stores share
  std::vector<SceneRanges> scenes;  // by scene index

  void clear();
};

std::vector<render::ValueRange> pack(const StepRanges& ranges);
// `ranges` must have the scene count of the packed value.
void unpack(std::span<const render::ValueRange> packed, StepRanges& ranges);

// Per scene, why this rank cannot render it this step (empty: it can). Agreed with a stage's
// outcome: a scene skipped on one rank is skipped on all, since its image would be incomplete.
using SceneSkips = std::vector<std::string>;

// Per scene, summed over the ranks for the timing log.
struct SceneCounters {
  std::uint64_t tets = 0;          // the solver's tets
  std::uint64_t kept_tets = 0;     // rendered: not ghost, not skipped
  std::uint64_t skipped_tets = 0;  // under nonfinite: skip_tets
  std::uint64_t bytes = 0;         // the renderer's copy and its BVH
};

std::vector<std::uint64_t> pack(std::span<const SceneCounters> counters);
void unpack(std::span<const std::uint64_t> packed, std::span<SceneCounters> counters);

}  // namespace tetray
