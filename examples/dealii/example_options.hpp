// The example's command line.
#pragma once

#include <optional>
#include <string>

#include "heat_parameters.hpp"

struct ExampleOptions {
  std::string config;  // tetray's YAML config
  HeatParameters heat;
  // Leave the ghost cells unflagged (to see what the flags do: each is then drawn twice).
  bool ghost_flags = true;
};

// The options, or nullopt with `error` saying which argument is wrong (or the usage, for --help).
std::optional<ExampleOptions> parse_options(int argc, char** argv, std::string& error);
