// The `probes:` key of the config (docs/config.md): sets of points and lines where
// fields are sampled at every rendered step.
#pragma once

#include <vector>

#include "adaptor/config/config.hpp"
#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {

// Longest list of points of all probe sets together (each point costs a search per step and a
// CSV row): a larger count is a config error.
inline constexpr std::size_t kMaxProbePoints = 1'000'000;

std::vector<ProbeSet> parse_probes(const YamlReader& r, const YAML::Node& node);

}  // namespace tetray::config
