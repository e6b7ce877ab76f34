// The output keys of the encoding (docs/config.md): image compression, the writer's
// threads and the movie.
#pragma once

#include "adaptor/config/config.hpp"

namespace YAML {
class Node;
}

namespace tetray::config {

class YamlReader;

// `png_compression`, `exr_compression`, `writer_threads` and `movie` of the `output` map into
// `out` (after `formats`).
void parse_encoding(const YamlReader& r, const YAML::Node& output, Output& out);

// What the writer passes to the encoders.
render::EncodeOptions encode_options(const Output& output);

}  // namespace tetray::config
