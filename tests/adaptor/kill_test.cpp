// Nothing torn by SIGKILL: a writer process (killed_writer_main.cpp) is killed at random moments,
// again and again, into one output directory, each run starting where the last could have got
// to and overlapping it (so runs both append rows and replace rows of steps rendered again).
// Before its kill, each run is also frozen (SIGSTOP) at many random moments and inspected: the
// files then are what a kill at that instant would leave, so one run samples many instants
// (a window of a few microseconds, such as an image written in place, is then hit within a
// run or two, which a few kills alone would rarely do). At every inspection and after every
// kill, every image under its final name decodes completely (PNG with libpng, EXR with
// OpenEXR), and every line of the Cinema table and the timing log is complete: it ends with a
// newline and has the header's column count; the table lists each step once, and only images
// that are on disk. A last run that is not killed leaves no temporary file behind.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "writer_process.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kKills = 6;
constexpr int kFreezesPerRun = 25;
constexpr int kStepsPerRun = 20;  // between runs' first steps: a run gets through more than this
constexpr int kWidth = 64, kHeight = 48;  // plane_config's image

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

// The inode, size and modification time of a file: whether it changed since it was checked.
struct FileVersion {
  ino_t inode = 0;
  off_t size = 0;
  long long mtime_ns = 0;
  bool operator==(const FileVersion&) const = default;
};

FileVersion version_of(const fs::path& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) return {};
  return {s.st_ino, s.st_size, s.st_mtim.tv_sec * 1'000'000'000LL + s.st_mtim.tv_nsec};
}

// What a kill at any moment may leave, checked file by file; an image is decoded again only
// when it changed since it was last found whole.
class TornFileCheck {
 public:
  explicit TornFileCheck(fs::path dir) : dir_(std::move(dir)) {}

  // Returns the lines of the log, which every run only appends to: how far the writers got.
  std::size_t expect_nothing_torn() {
    if (fs::exists(dir_ / "plane")) {
      for (const auto& entry : fs::directory_iterator(dir_ / "plane")) expect_whole_image(entry);
    }
    std::size_t log_lines = 0;
    if (const auto log = contents(dir_ / "tetray_log.csv")) {
      log_lines = complete_lines(dir_ / "tetray_log.csv", *log).size();
    }
    if (const auto table = contents(dir_ / "plane.cdb" / "data.csv")) {
      expect_rows_of_images_on_disk(complete_lines(dir_ / "plane.cdb" / "data.csv", *table));
    }
    return log_lines;
  }

 private:
  void expect_whole_image(const fs::directory_entry& entry) {
    const fs::path& p = entry.path();
    if (p.extension() != ".png" && p.extension() != ".exr") return;
    const FileVersion version = version_of(p);
    if (whole_[p.string()] == version) return;
    if (p.extension() == ".png") expect_whole_png(p);
    if (p.extension() == ".exr") expect_whole_exr(p);
    if (!::testing::Test::HasFailure()) whole_[p.string()] = version;
  }

  void expect_rows_of_images_on_disk(const std::vector<std::string>& lines) {
    const fs::path cdb = dir_ / "plane.cdb";
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

  fs::path dir_;
  std::map<std::string, FileVersion> whole_;
};

TEST(KilledRun, LeavesOnlyWholeImagesAndWholeLines) {
  ::alarm(120);  // a writer that hangs before its start byte ends the test instead of blocking it
  without_leak_check_in_writers();
  const ScratchDir dir;
  const fs::path log = dir.path() / "tetray_log.csv";
  TornFileCheck check(dir.path());
  std::mt19937 rng(20261201);  // fixed: the same delays every time
  std::uniform_int_distribution<int> delay_us(0, 4'000);
  std::size_t lines = 0;
  for (int run = 0; run < kKills; ++run) {
    const pid_t writer = start_writer(dir.path(), kStepsPerRun * run, 1'000'000);
    ASSERT_GT(writer, 0) << "the writer did not start";
    // The first instants of a run fall while it reopens its tables.
    for (int k = 0; k < kFreezesPerRun; ++k) {
      std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
      ASSERT_TRUE(freeze(writer));
      check.expect_nothing_torn();
      ASSERT_EQ(::kill(writer, SIGCONT), 0);
      if (::testing::Test::HasFailure()) break;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delay_us(rng)));
    ASSERT_TRUE(kill_writer(writer)) << "the writer ended on its own before it was killed";
    const std::size_t lines_after = check.expect_nothing_torn();
    EXPECT_GT(lines_after, lines) << "run " << run << " wrote no log row before its kill";
    lines = lines_after;
    if (::testing::Test::HasFailure()) return;
  }

  const pid_t last = start_writer(dir.path(), 0, 3);
  ASSERT_GT(last, 0);
  ASSERT_EQ(wait_writer(last), 0);
  check.expect_nothing_torn();
  for (const auto& entry : fs::recursive_directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "left behind: " << entry.path();
  }
  ::alarm(0);
}

}  // namespace
}  // namespace tetray::testing
