// The temporary files of write_file_atomically that a killed writer leaves: their names are
// recognised, and only those of a process that no longer exists, for a target the caller names,
// are removed; every other file stays.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <vector>

#include "render/image/image_write.hpp"
#include "support/scratch_dir.hpp"

namespace tetray::render {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

// The pid of a child that has exited and been reaped: a process that no longer exists.
long dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

void touch(const fs::path& path) { std::ofstream(path) << "partial"; }

TEST(TemporaryName, ParsesWhatWriteFileAtomicallyCreates) {
  const auto parsed = parse_temporary_name("scene_000012.png.tmp4242-7");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->target, "scene_000012.png");
  EXPECT_EQ(parsed->pid, 4242);
  // A name that holds ".tmp" itself: the last mark counts.
  const auto nested = parse_temporary_name("a.tmp1-2_000000.png.tmp99-0");
  ASSERT_TRUE(nested);
  EXPECT_EQ(nested->target, "a.tmp1-2_000000.png");
  EXPECT_EQ(nested->pid, 99);
}

TEST(TemporaryName, RejectsOtherNames) {
  for (const char* name :
       {"scene_000012.png", "data.csv.tmp", "data.csv.tmp12", "data.csv.tmp-1-0", "data.csv.tmp12-",
        "data.csv.tmp12-x", "data.csv.tmpab-0", "data.csv.tmp0-0", "data.csv.tmp12-0.bak",
        ".tmp12-0", "data.csv.tmp 12-0", "data.csv.tmp+12-0", "data.csv.tmp99999999999-0"}) {
    EXPECT_FALSE(parse_temporary_name(name)) << name;
  }
}

TEST(StaleTemporaries, RemovesOnlyThoseOfGoneWritersForNamedTargets) {
  const ScratchDir dir;
  const std::string gone = std::to_string(dead_pid());
  const std::string alive = std::to_string(::getpid());
  const fs::path stale = dir.path() / ("a.png.tmp" + gone + "-0");
  const fs::path live = dir.path() / ("a.png.tmp" + alive + "-3");
  const fs::path foreign = dir.path() / ("notes.txt.tmp" + gone + "-0");
  const fs::path unrelated = dir.path() / "a.png.tmp";
  const fs::path image = dir.path() / "a.png";
  for (const fs::path& p : {stale, live, foreign, unrelated, image}) touch(p);
  const fs::path link = dir.path() / ("b.png.tmp" + gone + "-1");
  fs::create_symlink(image, link);
  const fs::path folder = dir.path() / ("c.png.tmp" + gone + "-2");
  fs::create_directory(folder);

  const auto is_png = [](const std::string& name) { return name.ends_with(".png"); };
  const WriteResult removed = remove_stale_temporaries(dir.path().string(), is_png);
  ASSERT_TRUE(removed.ok) << removed.message;

  EXPECT_FALSE(fs::exists(stale));
  for (const fs::path& p : {live, foreign, unrelated, image, folder}) {
    EXPECT_TRUE(fs::exists(p)) << p;
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(testing::slurp(image), "partial");
}

TEST(StaleTemporaries, MissingDirectoryHasNone) {
  const ScratchDir dir;
  const WriteResult removed = remove_stale_temporaries((dir.path() / "absent").string(),
                                                       [](const std::string&) { return true; });
  EXPECT_TRUE(removed.ok) << removed.message;
}

// A writer really killed mid-write: a child whose file size limit stops write() with SIGXFSZ,
// which by default ends the process before it can rename or remove its temporary file. What it
// leaves carries its pid, is removed once it is gone, and the target keeps its old bytes.
TEST(StaleTemporaries, WhatAKilledWriterLeavesIsRemoved) {
  const ScratchDir dir;
  const std::string target = dir / "x.png";
  const unsigned char old_bytes[] = {1, 2, 3};
  ASSERT_TRUE(write_file_atomically(target, old_bytes).ok);

  const pid_t child = ::fork();
  if (child == 0) {
    const rlimit no_core{0, 0};
    const rlimit one_page{4096, 4096};
    ::setrlimit(RLIMIT_CORE, &no_core);
    ::setrlimit(RLIMIT_FSIZE, &one_page);
    const std::vector<unsigned char> large(1 << 16, 7);
    write_file_atomically(target, large);
    ::_exit(0);  // not reached: SIGXFSZ ends the child inside write()
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) << status;

  std::vector<fs::path> left;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    if (entry.path().filename() != "x.png") left.push_back(entry.path());
  }
  ASSERT_EQ(left.size(), 1u);
  const auto parsed = parse_temporary_name(left[0].filename().string());
  ASSERT_TRUE(parsed) << left[0];
  EXPECT_EQ(parsed->target, "x.png");
  EXPECT_EQ(parsed->pid, child);

  const WriteResult removed = remove_stale_temporaries(
      dir.path().string(), [](const std::string& name) { return name == "x.png"; });
  ASSERT_TRUE(removed.ok) << removed.message;
  EXPECT_FALSE(fs::exists(left[0]));
  EXPECT_EQ(testing::slurp(target), std::string("\1\2\3"));
}

}  // namespace
}  // namespace tetray::render
