// The output files across runs and against a hostile output directory: a second run into the same
// directory keeps the first run's Cinema rows of images still on disk and its log rows; a step
// rendered again replaces its row; a line torn by a killed run is cut; a symbolic link or FIFO
// where a table or folder belongs is refused with an io_error naming it, and nothing outside is
// touched; temporary files a killed run left are removed, and no other file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

class OutputFiles : public ::testing::Test {
 protected:
  // Creates an adaptor on the scratch directory, renders `steps` (time = step / 10), finalizes.
  Status run(const std::vector<std::int64_t>& steps, const std::string& output_keys = "",
             double time_offset = 0) {
    Status status;
    auto adaptor =
        Adaptor::create_from_yaml(MPI_COMM_WORLD, plane_config(out_.string(), output_keys), status);
    if (!adaptor) return status;
    const auto fields = scene_.fields();
    for (const std::int64_t step : steps) {
      status = adaptor->execute(step, time_offset + 0.1 * static_cast<double>(step), scene_.view(),
                                fields);
      if (!status.ok()) return status;
    }
    return adaptor->finalize();
  }

  fs::path image(int step, const char* extension = "png") const {
    return out_ / "plane" / ("plane_00000" + std::to_string(step) + "." + extension);
  }
  fs::path cinema() const { return out_ / "plane.cdb" / "data.csv"; }
  fs::path log() const { return out_ / "tetray_log.csv"; }

  // The steps the Cinema table lists, in order.
  std::vector<std::string> cinema_steps() const {
    std::vector<std::string> steps;
    const auto rows = read_csv(cinema().string());
    for (std::size_t r = 1; r < rows.size(); ++r) steps.push_back(cell(rows, r, "step"));
    return steps;
  }

  void SetUp() override {
    fs::create_directory(out_);
    fs::create_directory(elsewhere_);
  }

  ScratchDir dir_;
  const fs::path out_ = dir_.path() / "out";              // the output directory
  const fs::path elsewhere_ = dir_.path() / "elsewhere";  // a folder outside it
  PlaneScene scene_ = make_plane_scene(2);
};

void expect_io_error_naming(const Status& status, const fs::path& path, const std::string& what) {
  EXPECT_EQ(status.code, StatusCode::io_error) << status.message;
  EXPECT_NE(status.message.find(path.string()), std::string::npos) << status.message;
  EXPECT_NE(status.message.find(what), std::string::npos) << status.message;
}

TEST_F(OutputFiles, SecondRunKeepsTheFirstRunsRows) {
  ASSERT_TRUE(run({0, 1, 2}).ok());
  ASSERT_TRUE(run({3, 4}).ok());
  EXPECT_EQ(cinema_steps(), (std::vector<std::string>{"0", "1", "2", "3", "4"}));
  const auto rows = read_csv(cinema().string());
  EXPECT_EQ(cell(rows, 1, "FILE"), "../plane/plane_000000.png");
  EXPECT_EQ(cell(rows, 1, "FILE_exr"), "../plane/plane_000000.exr");
  EXPECT_EQ(read_csv(log().string()).size(), 1u + 5u);
}

TEST_F(OutputFiles, SecondRunDropsRowsOfImagesNoLongerOnDisk) {
  ASSERT_TRUE(run({0, 1, 2}).ok());
  fs::remove(image(1, "exr"));  // one of step 1's two images is gone: its row names a lost file
  ASSERT_TRUE(run({3}).ok());
  EXPECT_EQ(cinema_steps(), (std::vector<std::string>{"0", "2", "3"}));
}

// A re-run over the same steps (a solver restarted from step 0) overwrites the images; each
// step keeps one row, the newest, with the new run's time.
TEST_F(OutputFiles, StepRenderedAgainReplacesItsRow) {
  ASSERT_TRUE(run({0, 1, 2}).ok());
  ASSERT_TRUE(run({1, 2, 3}, "", 100).ok());
  EXPECT_EQ(cinema_steps(), (std::vector<std::string>{"0", "1", "2", "3"}));
  const auto rows = read_csv(cinema().string());
  EXPECT_EQ(cell(rows, 1, "time"), "0");
  EXPECT_EQ(cell(rows, 2, "time"), "100.1");
  EXPECT_EQ(cell(rows, 4, "time"), "100.3");
  EXPECT_EQ(read_csv(log().string()).size(), 1u + 6u);  // the log is a history: both runs
}

TEST_F(OutputFiles, TableOfOtherFormatsStartsAfresh) {
  ASSERT_TRUE(run({0, 1}, ", formats: [png]").ok());
  ASSERT_TRUE(run({2}).ok());
  const auto rows = read_csv(cinema().string());
  EXPECT_EQ(rows.at(0), (std::vector<std::string>{"time", "phi", "theta", "scene", "step", "FILE",
                                                  "FILE_exr"}));
  EXPECT_EQ(cinema_steps(), (std::vector<std::string>{"2"}));
}

// What a kill inside a write() that straddles a page can leave: a last line without its newline.
TEST_F(OutputFiles, LineTornByAKillIsCutAtTheNextStart) {
  ASSERT_TRUE(run({0, 1}).ok());
  for (const fs::path& table : {cinema(), log()}) {
    std::ofstream(table, std::ios::app) << "7,0.7,../plane/plane_0000";
  }
  ASSERT_TRUE(run({2}).ok());
  EXPECT_EQ(cinema_steps(), (std::vector<std::string>{"0", "1", "2"}));
  const auto log_rows = read_csv(log().string());
  ASSERT_EQ(log_rows.size(), 1u + 3u);
  for (std::size_t r = 1; r < log_rows.size(); ++r) {
    EXPECT_EQ(log_rows[r].size(), log_rows[0].size()) << "row " << r;
  }
  EXPECT_TRUE(slurp(log()).ends_with("\n"));
}

// The reported attack: a link planted in place of the log used to make the run truncate its
// target. Now creation fails naming the link, and the target keeps its bytes.
TEST_F(OutputFiles, SymbolicLinkInPlaceOfTheLogIsRefused) {
  const fs::path victim = elsewhere_ / "precious.txt";
  std::ofstream(victim) << "keep me\n";
  fs::create_symlink(victim, log());
  expect_io_error_naming(run({0}), log(), "symbolic link");
  EXPECT_EQ(slurp(victim), "keep me\n");
  EXPECT_FALSE(fs::exists(image(0)));
}

TEST_F(OutputFiles, SymbolicLinkInPlaceOfTheCinemaTableIsRefused) {
  const fs::path victim = elsewhere_ / "data.csv";
  std::ofstream(victim) << "step,time,FILE,FILE_exr\n";
  fs::create_directories(cinema().parent_path());
  fs::create_symlink(victim, cinema());
  expect_io_error_naming(run({0}), cinema(), "symbolic link");
  EXPECT_EQ(slurp(victim), "step,time,FILE,FILE_exr\n");
}

// A link in place of a folder tetray creates would put images and the table outside the tree.
TEST_F(OutputFiles, SymbolicLinkInPlaceOfAnOutputFolderIsRefused) {
  fs::create_directory_symlink(elsewhere_, out_ / "plane.cdb");
  expect_io_error_naming(run({0}), out_ / "plane.cdb", "symbolic link");
  EXPECT_TRUE(fs::is_empty(elsewhere_));
}

// A FIFO would block the writer forever in open() waiting for the other end. Should it block,
// the alarm ends the test (SIGALRM) instead of leaving it hanging.
TEST_F(OutputFiles, FifoInPlaceOfTheLogIsRefusedWithoutWaiting) {
  ASSERT_EQ(::mkfifo(log().c_str(), 0600), 0);
  ::alarm(20);
  const Status status = run({0});
  ::alarm(0);
  expect_io_error_naming(status, log(), "not a regular file");
}

// A link planted in place of the log during a run: the next append refuses it.
TEST_F(OutputFiles, SymbolicLinkPlantedDuringARunIsRefused) {
  const fs::path victim = elsewhere_ / "precious.txt";
  std::ofstream(victim) << "keep me\n";
  Status status;
  auto adaptor = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config(out_.string(), ", writer_queue_depth: 0"), status);
  ASSERT_TRUE(adaptor) << status.message;
  const auto fields = scene_.fields();
  ASSERT_TRUE(adaptor->execute(0, 0.0, scene_.view(), fields).ok());
  fs::remove(log());
  fs::create_symlink(victim, log());
  // Found while writing step 1, after the step's last agreement: every rank hears of it at the
  // next render step (README "Coupling a solver").
  ASSERT_TRUE(adaptor->execute(1, 0.1, scene_.view(), fields).ok());
  expect_io_error_naming(adaptor->execute(2, 0.2, scene_.view(), fields), log(), "symbolic link");
  EXPECT_EQ(slurp(victim), "keep me\n");
}

// The pid of a process that has exited and been reaped.
std::string gone_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return std::to_string(child);
}

// Every file under `root`, relative to it.
std::set<std::string> files_under(const fs::path& root) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_directory()) files.insert(fs::relative(entry.path(), root).string());
  }
  return files;
}

TEST_F(OutputFiles, StaleTemporariesOfAKilledRunAreRemovedAndNothingElse) {
  ASSERT_TRUE(run({0}, ", per_rank_images: true").ok());
  const std::string gone = gone_pid();
  const std::string alive = std::to_string(::getpid());
  const std::set<std::string> stale = {
      "plane/plane_000003.png.tmp" + gone + "-0",
      "plane/plane_000003.exr.tmp" + gone + "-1",
      "plane/ranks/plane_000003_rank0000.png.tmp" + gone + "-2",
      "plane.cdb/data.csv.tmp" + gone + "-3",
      "tetray_log.csv.tmp" + gone + "-4",
  };
  const std::set<std::string> kept = {
      "plane/plane_000003.png.tmp" + alive + "-9",                // its writer still runs
      "plane/ranks/plane_000003_rank0001.png.tmp" + gone + "-0",  // another rank's
      "plane/notes.txt.tmp" + gone + "-0",                        // not a name tetray writes
      "plane/other_000003.png.tmp" + gone + "-0",                 // another scene's name
      "plane.cdb/data.csv.bak",
      "notes.txt",
  };
  for (const auto& set : {stale, kept}) {
    for (const std::string& name : set) std::ofstream(out_ / name) << "x";
  }
  std::set<std::string> expected = files_under(out_);
  for (const std::string& name : stale) expected.erase(name);

  Status status;
  auto adaptor = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config(out_.string(), ", per_rank_images: true"), status);
  ASSERT_TRUE(adaptor) << status.message;
  EXPECT_EQ(files_under(out_), expected);
}

}  // namespace
}  // namespace tetray::testing
