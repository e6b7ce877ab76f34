// The writer that adaptor_kill_test kills: renders the plane scene (tests/adaptor/plane_scene.hpp)
// into DIR at steps FIRST, FIRST + 1, ... as fast as it can, through the writer thread, PNG and
// EXR (with MOVIE given as "movie": PNG and the movie), so that a kill lands while images, Cinema
// rows, log rows or movie frames are being written. It writes one byte to stdout once MPI is up,
// before the adaptor opens its files, so the killer's random delay covers the start (reopening
// the tables) too. Exits 1 on any error status.
#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "plane_scene.hpp"

namespace {

int render(const std::string& directory, long long first, long long count, bool movie) {
  using namespace tetray;
  Status status;
  const std::string formats = movie ? ", formats: [png, mp4]" : "";
  auto adaptor =
      Adaptor::create_from_yaml(MPI_COMM_WORLD, testing::plane_config(directory, formats), status);
  if (!adaptor) {
    std::fprintf(stderr, "killed_writer: %s\n", status.message.c_str());
    return 1;
  }
  const testing::PlaneScene scene = testing::make_plane_scene(2);
  const auto fields = scene.fields();
  for (long long step = first; step < first + count && status.ok(); ++step) {
    status = adaptor->execute(step, 0.1 * static_cast<double>(step), scene.view(), fields);
  }
  if (status.ok()) status = adaptor->finalize();
  if (!status.ok()) std::fprintf(stderr, "killed_writer: %s\n", status.message.c_str());
  return status.ok() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const bool movie = argc == 5 && std::string(argv[4]) == "movie";
  if (argc != 4 && !movie) {
    std::fprintf(stderr, "usage: killed_writer DIR FIRST_STEP STEPS [movie]\n");
    MPI_Finalize();
    return 2;
  }
  const char started = 's';
  if (::write(STDOUT_FILENO, &started, 1) != 1) return 1;
  const int code = render(argv[1], std::stoll(argv[2]), std::stoll(argv[3]), movie);
  MPI_Finalize();
  return code;
}
