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
  bool help = false;  // --help: print `usage` and stop
};

extern const char* const example_usage;

// The options, or nullopt with `error` saying which argument is wrong, followed by the usage.
std::optional<ExampleOptions> parse_options(int argc, char** argv, std::string& error);
