// The benchmarks' JSON output, written through jsoncpp: figures as numbers (null where a figure
// could not be measured, since JSON has no infinity or NaN) and the file written in one place.
#pragma once

#include <json/json.h>

#include <cstdint>
#include <string>

namespace tetray::bench {

Json::Value number(double value);
Json::Value count(std::uint64_t value);

// Writes `json` to `path` (two-space indentation, six significant digits: far below the timing
// noise); false when the file cannot be written.
bool write_json_file(const Json::Value& json, const std::string& path);

}  // namespace tetray::bench
