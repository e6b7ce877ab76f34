// Movies read back with FFmpeg's own demuxer and decoder, for the tests of the movie writer and
// of the adaptor's movie output.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tetray::testing {

struct DecodedMovie {
  std::string error;  // empty when the file could be opened and holds a video stream
  std::string codec;
  int frames = 0;
  int width = 0, height = 0;
  std::vector<std::uint8_t> first_luma;  // the first frame's Y plane, width x height
};

// Every frame of the movie's video stream, decoded.
DecodedMovie decode_movie(const std::string& path);

}  // namespace tetray::testing
