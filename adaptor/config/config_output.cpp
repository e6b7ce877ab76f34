#include "adaptor/config/config_output.hpp"

#include <string>
#include <vector>

#include "adaptor/config/yaml_reader.hpp"

namespace tetray::config {
namespace {

render::ExrCompression parse_exr_compression(const YamlReader& r, const YAML::Node& node) {
  const std::string key = "output.exr_compression";
  const std::string name = r.string(node, key);
  if (const auto compression = render::exr_compression_named(name)) return *compression;
  std::string names;
  for (const render::ExrCompressionInfo& c : render::exr_compressions()) {
    names += (names.empty() ? "" : ", ") + std::string(c.name);
  }
  r.fail(node, key, "'" + name + "' is none of " + names);
}

render::MovieOptions parse_movie(const YamlReader& r, const YAML::Node& node) {
  const std::string key = "output.movie";
  r.expect_map(node, key);
  r.allow_keys(node, key, {"fps", "quality"});
  render::MovieOptions movie;
  if (node["fps"]) {
    movie.frames_per_second = static_cast<int>(r.integer_in(node["fps"], key + ".fps", 1, 240));
  }
  if (node["quality"]) {
    movie.quality = static_cast<int>(r.integer_in(node["quality"], key + ".quality", 0, 51));
  }
  return movie;
}

}  // namespace

void parse_encoding(const YamlReader& r, const YAML::Node& output, Output& out) {
  if (output["png_compression"]) {
    out.png_compression = static_cast<int>(r.integer_in(
        output["png_compression"], "output.png_compression", 0, render::kMaxPngCompression));
  }
  if (output["exr_compression"]) {
    out.exr_compression = parse_exr_compression(r, output["exr_compression"]);
  }
  if (output["writer_threads"]) {
    out.writer_threads = static_cast<int>(
        r.integer_in(output["writer_threads"], "output.writer_threads", 1, kMaxThreads));
  }
  if (output["movie"]) out.movie = parse_movie(r, output["movie"]);
  if (out.mp4 && !out.exr && !out.png) {
    r.fail(output["formats"], "output.formats",
           "mp4 needs exr or png too: the movie's frames are the images written");
  }
}

render::EncodeOptions encode_options(const Output& output) {
  return {.exr_compression = output.exr_compression, .png_compression = output.png_compression};
}

}  // namespace tetray::config
