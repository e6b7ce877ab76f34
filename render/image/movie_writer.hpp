// A movie of a scene's images (docs/architecture.md §3): H.264 in fragmented MP4 through FFmpeg's
// libraries, one frame per image, appended as the images are written. Like an image, the movie
// appears under its name only whole: it is written to a temporary file next to it (named as
// write_file_atomically names its own, so that a later run removes one a killed process left)
// and renamed over the name by close. Until then an earlier movie of that name stays as it was;
// a movie never closed, or with a frame that failed midway, is removed, never published.
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
  // A movie to be closed into the file `path` (replacing it then), for frames of width x height
  // pixels. H.264 in 4:2:0 needs even sides: an odd side is padded by repeating the last column
  // or row. On failure (a directory at `path` included) returns null and sets `error`.
  static std::unique_ptr<MovieWriter> create(const std::string& path, int width, int height,
                                             const MovieOptions& options, std::string& error);
  ~MovieWriter();  // without close(): the movie is abandoned, its temporary file removed
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  // One frame: the image over black (the writer puts the scene's background under it first),
  // in sRGB. The image must have the size the movie was created with. After a frame that failed
  // in the encoder or the file, every call fails: the movie is not kept.
  WriteResult append(const Framebuffer& image);
  // Flushes the encoder, writes the end of the file and renames it to `path`; on failure the
  // file is removed and `path` left as it was. Further calls do nothing.
  WriteResult close();

  int frames() const;
  const std::string& path() const;

 private:
  struct State;
  explicit MovieWriter(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace tetray::render
