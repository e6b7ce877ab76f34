// Whole lines (adaptor/output/line_file.hpp) at the moment a write fails: a file size limit that
// falls inside a line makes the kernel write part of it and return short; the append must take that
// part back, and must not write the line in pieces, since a second write() past the limit ends
// the process with SIGXFSZ as a kill would, leaving the first piece behind. Also: a reader drops
// a last line without its newline.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>

#include "adaptor/output/line_file.hpp"
#include "support/scratch_dir.hpp"

namespace tetray {
namespace {

using testing::ScratchDir;
using testing::slurp;

TEST(LineFile, LineCutByTheFileSizeLimitIsTakenBack) {
  const ScratchDir dir;
  const std::string path = dir / "table.csv";
  const std::string header = "step,time,FILE";
  ASSERT_EQ(replace_lines(path, {header}), "");
  const std::string row = "12,1.5,../scene/scene_000012.png";

  const pid_t child = ::fork();
  if (child == 0) {
    // The limit falls in the middle of the row; SIGXFSZ keeps its default action (end the
    // process), so a second write() of the same line would be the kill.
    const rlim_t cut = header.size() + 1 + row.size() / 2;
    const rlimit limit{cut, cut};
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const std::string error = append_line(path, row);
    ::_exit(error.find("short write") != std::string::npos ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_FALSE(WIFSIGNALED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "no short-write error reported";
  EXPECT_EQ(slurp(path), header + '\n');
  EXPECT_EQ(append_line(path, row), "");
  EXPECT_EQ(slurp(path), header + '\n' + row + '\n');
}

TEST(LineFile, ReaderDropsALastLineWithoutItsNewline) {
  const ScratchDir dir;
  const std::string path = dir / "log.csv";
  std::ofstream(path) << "a,b\n1,2\n3,";
  const FileLines file = read_complete_lines(path);
  EXPECT_TRUE(file.error.empty()) << file.error;
  EXPECT_TRUE(file.exists);
  EXPECT_TRUE(file.torn);
  EXPECT_EQ(file.lines, (std::vector<std::string>{"a,b", "1,2"}));
  EXPECT_FALSE(read_complete_lines(dir / "absent.csv").exists);
}

}  // namespace
}  // namespace tetray
