#include "tools/bench_common/json_file.hpp"

#include <cmath>
#include <fstream>
#include <memory>

namespace tetray::bench {

Json::Value number(double value) {
  return std::isfinite(value) ? Json::Value(value) : Json::Value();
}

Json::Value count(std::uint64_t value) { return Json::Value(static_cast<Json::UInt64>(value)); }

bool write_json_file(const Json::Value& json, const std::string& path) {
  std::ofstream file(path);
  Json::StreamWriterBuilder builder;
  builder["indentation"] = "  ";
  builder["precision"] = 6;
  const std::unique_ptr<Json::StreamWriter> writer(builder.newStreamWriter());
  writer->write(json, &file);
  file << '\n';
  return static_cast<bool>(file);
}

}  // namespace tetray::bench
