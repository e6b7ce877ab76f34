#include "step_reductions.hpp"

#include <algorithm>

namespace tetray {
namespace {

constexpr std::size_t kRangesPerScene = 5;    // box x, y, z, color, then cap
constexpr std::size_t kCountersPerScene = 4;  // tets, kept, skipped, bytes

}  // namespace

void StepRanges::clear() {
  points = {};
  std::fill(scenes.begin(), scenes.end(), SceneRanges{});
}

std::vector<render::ValueRange> pack(const StepRanges& ranges) {
  std::vector<render::ValueRange> packed(std::begin(ranges.points.axis),
                                         std::end(ranges.points.axis));
  packed.reserve(3 + kRangesPerScene * ranges.scenes.size());
  for (const SceneRanges& scene : ranges.scenes) {
    packed.insert(packed.end(), std::begin(scene.box.axis), std::end(scene.box.axis));
    packed.push_back(scene.color);
    packed.push_back(scene.cap);
  }
  return packed;
}

void unpack(std::span<const render::ValueRange> packed, StepRanges& ranges) {
  std::copy_n(packed.begin(), 3, std::begin(ranges.points.axis));
  for (std::size_t k = 0; k < ranges.scenes.size(); ++k) {
    const auto scene = packed.subspan(3 + kRangesPerScene * k, kRangesPerScene);
    std::copy_n(scene.begin(), 3, std::begin(ranges.scenes[k].box.axis));
    ranges.scenes[k].color = scene[3];
    ranges.scenes[k].cap = scene[4];
  }
}

std::vector<std::uint64_t> pack(std::span<const SceneCounters> counters) {
  std::vector<std::uint64_t> packed;
  packed.reserve(kCountersPerScene * counters.size());
  for (const SceneCounters& c : counters) {
    packed.insert(packed.end(), {c.tets, c.kept_tets, c.skipped_tets, c.bytes});
  }
  return packed;
}

void unpack(std::span<const std::uint64_t> packed, std::span<SceneCounters> counters) {
  for (std::size_t k = 0; k < counters.size(); ++k) {
    const auto c = packed.subspan(kCountersPerScene * k, kCountersPerScene);
    counters[k] = {c[0], c[1], c[2], c[3]};
  }
}

}  // namespace tetray
