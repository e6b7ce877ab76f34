// A movie of a scene's images (docs/architecture.md §3): H.264 in fragmented MP4 through FFmpeg's
// libraries, one frame per image, appended as the images are written. Every frame is its own
// fragment, flushed to the file before append returns, so a process killed at any moment leaves
// a movie that plays up to the last frame appended before the kill (a fragment torn by the kill
// itself is ignored by demuxers); close writes the end of the file.
#pragma once

#include <memory>
#include <string>

#include "render/core/framebuffer.hpp"
#include "render/image/image_write.hpp"

namespace tetray::render {

struct MovieOptions {
  int frames_per_second = 24;
  int quality = 23;  // H.264 constant rate factor, 0 (lossless) .. 51; lower is better
  // Encoder threads: 1 keeps the encoder within the writer's share of the thread budget.
  int threads = 1;
};

// The codec FFmpeg's libraries offer for the movie: libx264's H.264 where present, else VP9 or
// MPEG-4 part 2 (all three go into MP4). Empty when there is none.
std::string movie_codec_name();

class MovieWriter {
 public:
  // Creates (or replaces) the file at `path` for frames of width x height pixels. H.264 in
  // 4:2:0 needs even sides: an odd side is padded by repeating the last column or row. On
  // failure returns null and sets `error`.
  static std::unique_ptr<MovieWriter> create(const std::string& path, int width, int height,
                                             const MovieOptions& options, std::string& error);
  ~MovieWriter();  // closes the file if close() was not called; errors are then lost
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  // One frame: the image over black (the writer puts the scene's background under it first),
  // in sRGB. The image must have the size the movie was created with.
  WriteResult append(const Framebuffer& image);
  // Flushes the encoder and writes the end of the file. Further calls do nothing.
  WriteResult close();

  int frames() const;
  const std::string& path() const;

 private:
  struct State;
  explicit MovieWriter(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace tetray::render
