#include "adaptor/config/config_probes.hpp"

#include <cctype>
#include <set>

#include "render/core/value_bounds.hpp"

namespace tetray::config {
namespace {

render::Vec3d probe_point(const YamlReader& r, const YAML::Node& node, const std::string& key) {
  const auto v = r.numbers_in(node, key, 3, 3, -render::kMaxCoordinate, render::kMaxCoordinate);
  return {v[0], v[1], v[2]};
}

bool valid_name(const std::string& name) {
  for (char ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') return false;
  }
  return !name.empty();
}

// A line from `from` to `to` sampled at `samples` evenly spaced points, both ends included.
void add_line(const YamlReader& r, const YAML::Node& node, const std::string& key, ProbeSet& set) {
  r.allow_keys(node, key, {"from", "to", "samples"});
  for (const char* k : {"from", "to", "samples"}) {
    if (!node[k]) r.fail(node, child_key(key, k), "missing (required)");
  }
  const render::Vec3d from = probe_point(r, node["from"], child_key(key, "from"));
  const render::Vec3d to = probe_point(r, node["to"], child_key(key, "to"));
  const auto samples = r.integer_in(node["samples"], child_key(key, "samples"), 2,
                                    static_cast<std::int64_t>(kMaxProbePoints));
  for (std::int64_t i = 0; i < samples; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(samples - 1);
    set.points.push_back(from + s * (to - from));
  }
}

ProbeSet parse_set(const YamlReader& r, const YAML::Node& node, const std::string& key) {
  r.allow_keys(node, key, {"name", "fields", "points", "lines"});
  for (const char* k : {"name", "fields"}) {
    if (!node[k]) r.fail(node, child_key(key, k), "missing (required)");
  }
  ProbeSet set;
  set.name = r.string(node["name"], child_key(key, "name"));
  if (!valid_name(set.name)) {
    r.fail(node["name"], child_key(key, "name"),
           "use only letters, digits, '_' and '-' (it names a file)");
  }
  const YAML::Node fields = node["fields"];
  r.expect_list(fields, child_key(key, "fields"));
  if (fields.size() == 0) r.fail(fields, child_key(key, "fields"), "name at least one field");
  for (std::size_t i = 0; i < fields.size(); ++i) {
    set.fields.push_back(r.string(fields[i], item_key(child_key(key, "fields"), i)));
  }
  if (const YAML::Node points = node["points"]) {
    r.expect_list(points, child_key(key, "points"));
    for (std::size_t i = 0; i < points.size(); ++i) {
      set.points.push_back(probe_point(r, points[i], item_key(child_key(key, "points"), i)));
    }
  }
  if (const YAML::Node lines = node["lines"]) {
    r.expect_list(lines, child_key(key, "lines"));
    for (std::size_t i = 0; i < lines.size(); ++i) {
      add_line(r, lines[i], item_key(child_key(key, "lines"), i), set);
    }
  }
  if (set.points.empty()) r.fail(node, key, "give points or lines");
  return set;
}

}  // namespace

std::vector<ProbeSet> parse_probes(const YamlReader& r, const YAML::Node& node) {
  r.expect_list(node, "probes");
  std::vector<ProbeSet> sets;
  std::set<std::string> names;
  std::size_t total = 0;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = item_key("probes", i);
    sets.push_back(parse_set(r, node[i], key));
    if (!names.insert(sets.back().name).second) {
      r.fail(node[i]["name"], child_key(key, "name"), "duplicate probe set name");
    }
    total += sets.back().points.size();
    if (total > kMaxProbePoints) {
      r.fail(node[i], key,
             "the probe sets hold more than " + std::to_string(kMaxProbePoints) + " points");
    }
  }
  return sets;
}

}  // namespace tetray::config
