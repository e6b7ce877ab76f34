// A movie being written when the run is killed (SIGKILL): under its final name there is only ever
// a movie that a run finished. A first run finishes the movie of steps 0-4. Then writers
// (killed_writer_main.cpp) are killed at random moments once they have appended frames to their
// own movies, alternately one starting at step 0 (the finished movie's name) and one starting at
// a later step (a name of its own). Each is also frozen at random moments and inspected, which
// sees what a kill at that instant would leave (kill_test.cpp samples images the same way). At
// every inspection and after every kill, the only movie under a final name is the finished one,
// byte for byte. A last run that finishes replaces it by its own, which FFmpeg decodes to its
// frames, and leaves no temporary file of the killed runs behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <thread>

#include "support/movie_read.hpp"
#include "support/scratch_dir.hpp"
#include "writer_process.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kKills = 4;
constexpr int kFreezesPerRun = 25;
constexpr int kWidth = 64, kHeight = 48;  // plane_config's image

// The movies under their final names (`<scene>_<step>.mp4`), by name, with their size and a hash
// of their bytes.
std::map<std::string, std::string> final_movies(const fs::path& dir) {
  std::map<std::string, std::string> movies;
  if (!fs::exists(dir / "plane")) return movies;
  for (const auto& entry : fs::directory_iterator(dir / "plane")) {
    if (entry.path().extension() != ".mp4") continue;
    const std::string bytes = slurp(entry.path());
    movies[entry.path().filename().string()] = std::to_string(bytes.size()) + " bytes, hash " +
                                               std::to_string(std::hash<std::string>{}(bytes));
  }
  return movies;
}

// Files whose name holds a temporary's mark: a movie, image or table being written.
std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos) found.push_back(name);
  }
  return found;
}

std::size_t log_rows(const fs::path& dir) {
  const std::string log = slurp(dir / "tetray_log.csv");
  return static_cast<std::size_t>(std::count(log.begin(), log.end(), '\n'));
}

// Waits (at most 20 s) until the writer has logged `rows` rows: the movie has frames then, since
// each image's movie frame follows its log row.
bool wait_for_log_rows(const fs::path& dir, std::size_t rows) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (log_rows(dir) < rows) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

void expect_whole_movie(const fs::path& path, int frames) {
  const DecodedMovie movie = decode_movie(path.string());
  EXPECT_TRUE(movie.error.empty()) << path << ": " << movie.error;
  EXPECT_EQ(movie.frames, frames) << path;
  EXPECT_EQ(movie.width, kWidth) << path;
  EXPECT_EQ(movie.height, kHeight) << path;
}

TEST(KilledMovie, LeavesOnlyFinishedMoviesUnderTheirNames) {
  ::alarm(180);  // a writer that hangs before its start byte ends the test instead of blocking it
  without_leak_check_in_writers();
  const ScratchDir dir;
  const fs::path movie = dir.path() / "plane" / "plane_000000.mp4";
  const pid_t first = start_writer(dir.path(), 0, 5, true);
  ASSERT_GT(first, 0);
  ASSERT_EQ(wait_writer(first), 0);
  expect_whole_movie(movie, 5);
  const std::map<std::string, std::string> finished = final_movies(dir.path());
  ASSERT_EQ(finished.size(), 1u);

  std::mt19937 rng(20261202);  // fixed: the same delays every time
  std::uniform_int_distribution<int> delay_us(0, 4'000);
  for (int run = 0; run < kKills; ++run) {
    const long long first_step = run % 2 == 0 ? 0 : 1000 * run;
    const std::size_t rows_before = log_rows(dir.path());
    const pid_t writer = start_writer(dir.path(), first_step, 1'000'000, true);
    ASSERT_GT(writer, 0) << "the writer did not start";
    for (int k = 0; k < kFreezesPerRun; ++k) {
      std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
      ASSERT_TRUE(freeze(writer));
      EXPECT_EQ(final_movies(dir.path()), finished) << "run " << run << ", inspection " << k;
      ASSERT_EQ(::kill(writer, SIGCONT), 0);
      if (::testing::Test::HasFailure()) break;
    }
    // Two more log rows: this run's movie has a frame and the writer is on with the next.
    const bool mid_movie = wait_for_log_rows(dir.path(), rows_before + 2);
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    ASSERT_TRUE(kill_writer(writer)) << "the writer ended on its own before it was killed";
    ASSERT_TRUE(mid_movie) << "run " << run << " logged no two rows in 20 s";
    EXPECT_EQ(final_movies(dir.path()), finished) << "after the kill of run " << run;
    if (::testing::Test::HasFailure()) return;
  }

  const pid_t last = start_writer(dir.path(), 0, 3, true);
  ASSERT_GT(last, 0);
  ASSERT_EQ(wait_writer(last), 0);
  const std::map<std::string, std::string> movies = final_movies(dir.path());
  ASSERT_EQ(movies.size(), 1u) << "a killed run left its movie under " << movies.rbegin()->first;
  expect_whole_movie(movie, 3);
  EXPECT_EQ(temporaries(dir.path()), std::vector<std::string>{});
  ::alarm(0);
}

}  // namespace
}  // namespace tetray::testing
