// The tools' exit status on the command line, as the README promises: 1 for a usage error (an
// unknown option, a missing or invalid argument; CLI11's own codes are 105 to 109), 0 for --help.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace tetray {
namespace {

int exit_status(const std::string& command) {
  const int status = std::system((command + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Tool {
  const char* executable;
  const char* invalid_value;  // arguments with a value its validator refuses
};

class CliExit : public ::testing::TestWithParam<Tool> {};

TEST_P(CliExit, UsageErrorsExitWithOneAndHelpWithZero) {
  const std::string exe = GetParam().executable;
  EXPECT_EQ(exit_status(exe + " --no-such-option"), 1);
  EXPECT_EQ(exit_status(exe + " " + GetParam().invalid_value), 1);
  EXPECT_EQ(exit_status(exe + " --help"), 0);
}

INSTANTIATE_TEST_SUITE_P(Tools, CliExit,
                         ::testing::Values(Tool{TETRAY_RENDER_EXE,
                                                "grid.vtu --field f --iso 0 -o out.png --size 0x4"},
                                           Tool{TETRAY_REPLAY_EXE, "-c"},
                                           Tool{TETRAY_COMPOSITE_BENCH_EXE, "--repeat many"},
                                           Tool{TETRAY_ADAPTOR_BENCH_EXE, "-n many"}),
                         [](const ::testing::TestParamInfo<Tool>& tool) {
                           std::string name =
                               std::filesystem::path(tool.param.executable).filename().string();
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace tetray
