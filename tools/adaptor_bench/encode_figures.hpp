// Encoding figures of tetray-adaptor-bench: how long each image format and compression takes for
// one rendered image, and how large the file is, one thread each (the writer's cost in CPU time).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/core/framebuffer.hpp"

namespace tetray::bench {

struct EncodeFigure {
  std::string format;       // "png", "exr" or "mp4"
  std::string compression;  // "level 1", "zip", "h264 crf 23", ...
  bool lossless = true;
  std::string note;       // what a lossy compression loses
  double ms = 0;          // best of the runs
  std::size_t bytes = 0;  // the file (for the movie: per frame, averaged)
};

// The image a run wrote, read back from its EXR (half RGBA, float depth), as a framebuffer.
std::optional<render::Framebuffer> read_exr_image(const std::string& path, std::string& error);

// Every PNG level in `png_levels`, every EXR compression of OpenEXR 3.1, and a frame of the
// movie, each timed `runs` times on one thread.
std::vector<EncodeFigure> encode_figures(const render::Framebuffer& image,
                                         const std::vector<int>& png_levels, int runs,
                                         const std::string& scratch_dir);

}  // namespace tetray::bench
