#include "adaptor/config/yaml_reader.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::config {
namespace {

std::string joined(std::initializer_list<std::string_view> words) {
  std::string out;
  for (std::string_view w : words) {
    if (!out.empty()) out += ", ";
    out += w;
  }
  return out;
}

}  // namespace

void YamlReader::fail(const YAML::Node& node, std::string_view key, std::string_view what) const {
  std::string where = source_;
  const YAML::Mark mark = node.Mark();
  if (!mark.is_null()) {
    where += ':' + std::to_string(mark.line + 1) + ':' + std::to_string(mark.column + 1);
  }
  throw LocatedError(where + ": " + std::string(key) + ": " + std::string(what));
}

void YamlReader::expect_map(const YAML::Node& node, std::string_view key) const {
  if (!node.IsMap()) fail(node, key, "expected a map of keys");
}

void YamlReader::expect_list(const YAML::Node& node, std::string_view key) const {
  if (!node.IsSequence()) fail(node, key, "expected a list");
}

void YamlReader::allow_keys(const YAML::Node& map, std::string_view key,
                            std::initializer_list<std::string_view> allowed) const {
  expect_map(map, key);
  for (const auto& entry : map) {
    const std::string name = entry.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      fail(entry.first, child_key(key, name), "unknown key (allowed: " + joined(allowed) + ")");
    }
  }
}

double YamlReader::number(const YAML::Node& node, std::string_view key) const {
  double value = 0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
    fail(node, key, "expected a number");
  }
  if (!std::isfinite(value)) fail(node, key, "expected a finite number");
  return value;
}

double YamlReader::number_in(const YAML::Node& node, std::string_view key, double lo,
                             double hi) const {
  const double value = number(node, key);
  if (value < lo || value > hi) {
    fail(node, key,
         "value " + node.Scalar() + " is outside [" + std::to_string(lo) + ", " +
             std::to_string(hi) + "]");
  }
  return value;
}

std::int64_t YamlReader::integer(const YAML::Node& node, std::string_view key) const {
  std::int64_t value = 0;
  if (!node.IsScalar() || !YAML::convert<std::int64_t>::decode(node, value)) {
    fail(node, key, "expected an integer");
  }
  return value;
}

std::int64_t YamlReader::integer_in(const YAML::Node& node, std::string_view key, std::int64_t lo,
                                    std::int64_t hi) const {
  const std::int64_t value = integer(node, key);
  if (value < lo || value > hi) {
    fail(node, key,
         "value " + std::to_string(value) + " is outside [" + std::to_string(lo) + ", " +
             std::to_string(hi) + "]");
  }
  return value;
}

bool YamlReader::boolean(const YAML::Node& node, std::string_view key) const {
  bool value = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
    fail(node, key, "expected true or false");
  }
  return value;
}

std::string YamlReader::string(const YAML::Node& node, std::string_view key) const {
  if (!node.IsScalar() || node.Scalar().empty()) fail(node, key, "expected a non-empty string");
  return node.Scalar();
}

std::string YamlReader::choice(const YAML::Node& node, std::string_view key,
                               std::initializer_list<std::string_view> choices) const {
  std::string value = string(node, key);
  if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
    fail(node, key, "'" + value + "' is not one of: " + joined(choices));
  }
  return value;
}

std::vector<double> YamlReader::numbers(const YAML::Node& node, std::string_view key,
                                        std::size_t min_size, std::size_t max_size) const {
  expect_list(node, key);
  if (node.size() < min_size || node.size() > max_size) {
    const std::string size = min_size == max_size
                                 ? std::to_string(min_size)
                                 : std::to_string(min_size) + " to " + std::to_string(max_size);
    fail(node, key, "expected a list of " + size + " numbers, got " + std::to_string(node.size()));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) out.push_back(number(node[i], item_key(key, i)));
  return out;
}

std::vector<double> YamlReader::numbers_in(const YAML::Node& node, std::string_view key,
                                           std::size_t min_size, std::size_t max_size, double lo,
                                           double hi) const {
  std::vector<double> out = numbers(node, key, min_size, max_size);
  for (std::size_t i = 0; i < out.size(); ++i) number_in(node[i], item_key(key, i), lo, hi);
  return out;
}

std::string child_key(std::string_view parent, std::string_view child) {
  return parent.empty() ? std::string(child) : std::string(parent) + '.' + std::string(child);
}

std::string item_key(std::string_view list, std::size_t index) {
  return std::string(list) + '[' + std::to_string(index) + ']';
}

}  // namespace tetray::config
