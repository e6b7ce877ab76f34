// Reads and validates the whole adaptor config at create time (DESIGN §4): unknown keys, wrong
// types and impossible values are errors that name the source, the line and the key.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "config.hpp"

namespace tetray::config {

struct ParseResult {
  std::optional<Config> config;  // empty on error
  std::string error;
};

// `source` names the text in messages (a file name, or "<yaml string>").
ParseResult parse_config(std::string_view yaml, const std::string& source);
ParseResult load_config_file(const std::string& path);

}  // namespace tetray::config
