// The movie writer of a build without FFmpeg (-DTETRAY_MOVIES=OFF, as scripts/setup.sh --demo
// builds it): every movie fails to open with a message that says why and how to get movies, and
// the images of the same step are written as usual.
#include <utility>

#include "render/image/movie_writer.hpp"

namespace tetray::render {

struct MovieWriter::State {
  std::string path;
};

std::string movie_codec_name() { return {}; }

MovieWriter::MovieWriter(std::unique_ptr<State> state) : state_(std::move(state)) {}

MovieWriter::~MovieWriter() = default;

std::unique_ptr<MovieWriter> MovieWriter::create(const std::string& path, int, int,
                                                 const MovieOptions&, std::string& error) {
  error = "movie '" + path +
          "': this tetray was built without FFmpeg (-DTETRAY_MOVIES=OFF); configure with "
          "-DTETRAY_MOVIES=ON (scripts/setup.sh without --demo installs FFmpeg) for movies";
  return nullptr;
}

WriteResult MovieWriter::append(const Framebuffer&) {
  return {false, "movie '" + state_->path + "': no movie writer in this build"};
}

WriteResult MovieWriter::close() { return {true, {}}; }

int MovieWriter::frames() const { return 0; }

const std::string& MovieWriter::path() const { return state_->path; }

}  // namespace tetray::render
