// Typed access to a YAML tree that turns every problem into one message naming the source
// file, the line and the key (docs/config.md). Used only while parsing the config; the
// error is carried out of the parser as a value (config_parse.hpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tetray::config {

// Thrown only inside the parser and caught by parse_config; never crosses the adaptor API.
class LocatedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class YamlReader {
 public:
  explicit YamlReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const YAML::Node& node, std::string_view key, std::string_view what) const;

  void expect_map(const YAML::Node& node, std::string_view key) const;
  void expect_list(const YAML::Node& node, std::string_view key) const;
  // Rejects any key of `map` not in `allowed`, naming it and listing the allowed ones.
  void allow_keys(const YAML::Node& map, std::string_view key,
                  std::initializer_list<std::string_view> allowed) const;

  double number(const YAML::Node& node, std::string_view key) const;  // finite
  double number_in(const YAML::Node& node, std::string_view key, double lo, double hi) const;
  std::int64_t integer(const YAML::Node& node, std::string_view key) const;
  std::int64_t integer_in(const YAML::Node& node, std::string_view key, std::int64_t lo,
                          std::int64_t hi) const;
  bool boolean(const YAML::Node& node, std::string_view key) const;
  std::string string(const YAML::Node& node, std::string_view key) const;
  // One of `choices`.
  std::string choice(const YAML::Node& node, std::string_view key,
                     std::initializer_list<std::string_view> choices) const;
  // A list of numbers with a length in [min_size, max_size].
  std::vector<double> numbers(const YAML::Node& node, std::string_view key, std::size_t min_size,
                              std::size_t max_size) const;
  // The same, each number in [lo, hi].
  std::vector<double> numbers_in(const YAML::Node& node, std::string_view key, std::size_t min_size,
                                 std::size_t max_size, double lo, double hi) const;

 private:
  std::string source_;
};

// "scenes[2].camera" style key paths for messages.
std::string child_key(std::string_view parent, std::string_view child);
std::string item_key(std::string_view list, std::size_t index);

}  // namespace tetray::config
