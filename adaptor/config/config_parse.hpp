// Reads and validates the whole adaptor config at create time (docs/config.md): unknown
// keys, wrong types and impossible values are errors that name the source, the line and the key.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "adaptor/config/config.hpp"

namespace tetray::config {

struct ParseResult {
  std::optional<Config> config;  // empty on error
  std::string error;
};

// `source` names the text in messages (a file name, or "<yaml string>"). `rank_count` is the
// size of the communicator the config is for: output.writer_rank must name one of its ranks.
ParseResult parse_config(std::string_view yaml, const std::string& source, int rank_count = 1);
ParseResult load_config_file(const std::string& path, int rank_count = 1);

}  // namespace tetray::config
