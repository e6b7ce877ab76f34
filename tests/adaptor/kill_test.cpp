// Nothing torn by SIGKILL: a writer process (killed_writer_main.cpp) is killed at random moments,
// again and again, into one output directory, each run starting where the last could have got
// to and overlapping it (so runs both append rows and replace rows of steps rendered again).
// After every kill, every image under its final name decodes completely (PNG with libpng, EXR with
// OpenEXR), and every line of the Cinema table and the timing log is complete: it ends with a
// newline and has the header's column count; the table lists each step once, and only images
// that are on disk. A last run that is not killed leaves no temporary file behind.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <set>
#include <thread>

#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"

extern char** environ;

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kKills = 10;
constexpr int kStepsPerRun = 20;          // a run's first step: a killed run gets through a few
constexpr int kWidth = 64, kHeight = 48;  // plane_config's image

// Starts the writer; returns its pid once it has written its start byte (-1 if it died first).
pid_t start_writer(const fs::path& dir, long long first_step, long long steps) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  const std::string dir_arg = dir.string(), first = std::to_string(first_step),
                    count = std::to_string(steps);
  char* argv[] = {const_cast<char*>(TETRAY_KILLED_WRITER), const_cast<char*>(dir_arg.c_str()),
                  const_cast<char*>(first.c_str()), const_cast<char*>(count.c_str()), nullptr};
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, TETRAY_KILLED_WRITER, &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  char started = 0;
  const bool ready = spawned == 0 && ::read(pipe_fds[0], &started, 1) == 1;
  ::close(pipe_fds[0]);
  if (spawned == 0 && !ready) ::waitpid(pid, nullptr, 0);
  return ready ? pid : -1;
}

// Every byte of the file; nullopt when it does not exist.
std::optional<std::string> contents(const fs::path& path) {
  if (!fs::exists(path)) return std::nullopt;
  return slurp(path);
}

std::size_t column_count(const std::string& line) {
  return static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
}

// The lines of a CSV file, each checked whole; ASSERT-style failures name the file and line.
std::vector<std::string> complete_lines(const fs::path& path, const std::string& text) {
  std::vector<std::string> lines;
  EXPECT_TRUE(text.empty() || text.back() == '\n') << path << " ends in a torn line";
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    lines.push_back(text.substr(start, end - start));
  }
  if (lines.empty()) {
    ADD_FAILURE() << path << " has no header";
    return lines;
  }
  for (std::size_t k = 1; k < lines.size(); ++k) {
    EXPECT_EQ(column_count(lines[k]), column_count(lines[0]))
        << path << " line " << k + 1 << ": " << lines[k];
  }
  return lines;
}

void expect_whole_exr(const fs::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    ASSERT_EQ(width, kWidth) << path;
    ASSERT_EQ(height, kHeight) << path;
    std::vector<float> values(5 * static_cast<std::size_t>(width) * height);
    Imf::FrameBuffer slices;
    const char* channels[] = {"R", "G", "B", "A", "Z"};
    for (std::size_t c = 0; c < 5; ++c) {
      ASSERT_NE(file.header().channels().findChannel(channels[c]), nullptr) << path;
      slices.insert(channels[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data() + c),
                                            5 * sizeof(float), 5 * sizeof(float) * width));
    }
    file.setFrameBuffer(slices);
    file.readPixels(window.min.y, window.max.y);
    EXPECT_TRUE(file.isComplete()) << path;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": " << e.what();
  }
}

void expect_whole_png(const fs::path& path) {
  const PngPixels png = read_png_rgba8(path.string());
  EXPECT_TRUE(png.error.empty()) << path << ": " << png.error;
  EXPECT_EQ(png.width, kWidth) << path;
  EXPECT_EQ(png.height, kHeight) << path;
}

// What a kill at any moment may leave, checked file by file. Returns the lines of the log, which
// every run only appends to: how far the writers got.
std::size_t expect_nothing_torn(const fs::path& dir) {
  if (fs::exists(dir / "plane")) {
    for (const auto& entry : fs::directory_iterator(dir / "plane")) {
      const fs::path& p = entry.path();
      if (p.extension() == ".png") expect_whole_png(p);
      if (p.extension() == ".exr") expect_whole_exr(p);
    }
  }
  std::size_t log_lines = 0;
  if (const auto log = contents(dir / "tetray_log.csv")) {
    log_lines = complete_lines(dir / "tetray_log.csv", *log).size();
  }
  const fs::path cdb = dir / "plane.cdb";
  if (const auto table = contents(cdb / "data.csv")) {
    const std::vector<std::string> lines = complete_lines(cdb / "data.csv", *table);
    std::set<std::string> steps;
    for (std::size_t k = 1; k < lines.size(); ++k) {
      const std::string& row = lines[k];
      EXPECT_TRUE(steps.insert(row.substr(0, row.find(','))).second) << "listed twice: " << row;
      for (std::size_t comma = row.find(",../"); comma != std::string::npos;
           comma = row.find(",../", comma + 1)) {
        const std::string file = row.substr(comma + 1, row.find(',', comma + 1) - comma - 1);
        EXPECT_TRUE(fs::exists(cdb / file)) << "listed but not on disk: " << file;
      }
    }
  }
  return log_lines;
}

TEST(KilledRun, LeavesOnlyWholeImagesAndWholeLines) {
  ::alarm(120);  // a writer that hangs before its start byte ends the test instead of blocking it
  // The writer starts MPI, whose own allocations LeakSanitizer would report when it exits
  // (tests/support/lsan_options.cpp); the last option given wins.
  const char* asan = std::getenv("ASAN_OPTIONS");
  ::setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":detect_leaks=0").c_str(), 1);
  const ScratchDir dir;
  std::mt19937 rng(20261201);  // fixed: the same delays every time
  std::uniform_int_distribution<int> delay_us(0, 60'000);
  int killed_while_writing = 0;
  for (int run = 0; run < kKills; ++run) {
    const pid_t writer = start_writer(dir.path(), kStepsPerRun * run / 2, 1'000'000);
    ASSERT_GT(writer, 0) << "the writer did not start";
    const std::size_t lines_before = expect_nothing_torn(dir.path());
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    ASSERT_EQ(::kill(writer, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(writer, &status, 0), writer);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
        << "the writer ended on its own (status " << status << ") before it was killed";
    killed_while_writing += expect_nothing_torn(dir.path()) > lines_before;
    if (::testing::Test::HasFailure()) return;
  }
  // Most kills must land after the writer wrote something, or the test checks little.
  EXPECT_GE(killed_while_writing, kKills / 2);

  const pid_t last = start_writer(dir.path(), 0, 3);
  ASSERT_GT(last, 0);
  int status = 0;
  ASSERT_EQ(::waitpid(last, &status, 0), last);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  expect_nothing_torn(dir.path());
  for (const auto& entry : fs::recursive_directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "left behind: " << entry.path();
  }
  ::alarm(0);
}

}  // namespace
}  // namespace tetray::testing
