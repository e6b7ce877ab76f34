#include "example_options.hpp"

#include <charconv>
#include <cmath>
#include <string_view>

const char* const example_usage =
    "usage: dealii_heat_insitu [--config FILE] [--steps N] [--dt DT] [--refine-every N]\n"
    "                          [--max-level N] [--source-width W] [--without-ghost-flags]\n"
    "  --config FILE      tetray's config (default: heat_insitu.yaml beside the sources)\n"
    "  --steps N          time steps, 1..100000 (default 24); the source circles once\n"
    "  --dt DT            time step, > 0 (default 0.005)\n"
    "  --refine-every N   adapt the mesh every N steps, 0 never (default 3)\n"
    "  --max-level N      finest refinement level, 3..8 (default 5)\n"
    "  --source-width W   the Gaussian source's standard deviation, > 0 (default 0.08)\n"
    "  --without-ghost-flags  pass deal.II's ghost cells unflagged: each is drawn twice\n";

namespace {

bool read_number(std::string_view text, unsigned int& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

bool read_number(std::string_view text, double& value) {
  try {
    std::size_t used = 0;
    value = std::stod(std::string(text), &used);
    return used == text.size() && std::isfinite(value);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

std::optional<ExampleOptions> parse_options(int argc, char** argv, std::string& error) {
  ExampleOptions options{DEALII_EXAMPLE_CONFIG, {}};
  HeatParameters& heat = options.heat;
  for (int i = 1; i < argc; ++i) {
    const std::string_view name = argv[i];
    if (name == "--help" || name == "-h") {
      options.help = true;
      return options;
    }
    if (name == "--without-ghost-flags") {
      options.ghost_flags = false;
      continue;
    }
    const bool known = name == "--config" || name == "--steps" || name == "--dt" ||
                       name == "--refine-every" || name == "--max-level" ||
                       name == "--source-width";
    if (!known || i + 1 >= argc) {
      error =
          std::string(name) + (known ? ": missing value\n" : ": unknown option\n") + example_usage;
      return std::nullopt;
    }
    const std::string_view value = argv[++i];
    bool good = true;
    if (name == "--config") {
      options.config = value;
    } else if (name == "--steps") {
      good = read_number(value, heat.steps) && heat.steps >= 1 && heat.steps <= 100000;
    } else if (name == "--dt") {
      good = read_number(value, heat.dt) && heat.dt > 0;
    } else if (name == "--refine-every") {
      good = read_number(value, heat.refine_every);
    } else if (name == "--max-level") {
      good = read_number(value, heat.max_level) && heat.max_level >= heat.initial_refinement &&
             heat.max_level <= 8;
    } else {  // --source-width
      good = read_number(value, heat.source_width) && heat.source_width > 0;
    }
    if (!good) {
      error = std::string(name) + ": bad value '" + std::string(value) + "'\n" + example_usage;
      return std::nullopt;
    }
  }
  return options;
}
