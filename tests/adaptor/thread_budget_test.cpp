// The renderer's default thread count: the affinity mask the process runs under, capped by its
// cgroup's CPU quota, and what the timing log says the adaptor used. ctest runs the suite
// ThreadBudgetUnderTaskset only under `taskset`, with the count it expects in
// TETRAY_EXPECTED_THREADS (and leaves it out of the plain run); the quota parsing runs on cgroup
// files written here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "adaptor/step/thread_budget.hpp"
#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"

namespace tetray {
namespace {

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(ThreadBudgetUnderTaskset, FollowsTheAffinityMaskItRunsUnder) {
  const char* expected = std::getenv("TETRAY_EXPECTED_THREADS");
  ASSERT_NE(expected, nullptr) << "run under taskset by ctest (adaptor_thread_budget_taskset_*)";
  const int cpus = std::atoi(expected);
  EXPECT_EQ(cpus_in_affinity_mask(), cpus);
  // A cgroup quota below the mask (none on the machines of this project's CI) lowers it.
  const std::optional<double> quota = cgroup_cpu_quota(own_cgroup_dir());
  EXPECT_EQ(default_thread_count(), quota && *quota < cpus ? std::max(1, int(*quota)) : cpus);
}

// The threads the adaptor rendered with, from its timing log.
std::string logged_threads(const std::string& top_lines) {
  const testing::ScratchDir dir;
  Status status;
  const std::string out = dir / "out";
  auto adaptor =
      Adaptor::create_from_yaml(MPI_COMM_WORLD, testing::plane_config(out, "", top_lines), status);
  EXPECT_TRUE(adaptor) << status.message;
  if (!adaptor) return {};
  const testing::PlaneScene scene = testing::make_plane_scene(2);
  EXPECT_TRUE(adaptor->execute(0, 0, scene.view(), scene.fields()).ok());
  EXPECT_TRUE(adaptor->finalize().ok());
  return testing::cell(testing::read_csv(out + "/tetray_log.csv"), 1, "threads");
}

TEST(ThreadBudgetUnderTaskset, TheAdaptorRendersWithTheDefaultAndLogsIt) {
  const char* expected = std::getenv("TETRAY_EXPECTED_THREADS");
  ASSERT_NE(expected, nullptr) << "run under taskset by ctest (adaptor_thread_budget_taskset_*)";
  EXPECT_EQ(logged_threads(""), std::to_string(default_thread_count()));
}

TEST(ThreadBudget, TheThreadsKeyOverridesTheDefault) {
  EXPECT_EQ(logged_threads("threads: 3\n"), "3");
}

TEST(ThreadBudget, ReadsACgroupV2Quota) {
  const testing::ScratchDir dir;
  write(dir / "cpu.max", "250000 100000\n");
  EXPECT_DOUBLE_EQ(cgroup_cpu_quota(dir.path().string()).value_or(0), 2.5);
  write(dir / "cpu.max", "max 100000\n");
  EXPECT_FALSE(cgroup_cpu_quota(dir.path().string()));
}

TEST(ThreadBudget, ReadsACgroupV1Quota) {
  const testing::ScratchDir dir;
  write(dir / "cpu.cfs_period_us", "100000\n");
  write(dir / "cpu.cfs_quota_us", "150000\n");
  EXPECT_DOUBLE_EQ(cgroup_cpu_quota(dir.path().string()).value_or(0), 1.5);
  write(dir / "cpu.cfs_quota_us", "-1\n");
  EXPECT_FALSE(cgroup_cpu_quota(dir.path().string()));
}

TEST(ThreadBudget, NoQuotaWhereNoCgroupFilesAre) {
  const testing::ScratchDir dir;
  EXPECT_FALSE(cgroup_cpu_quota(dir.path().string()));
  write(dir / "cpu.max", "garbage\n");
  EXPECT_FALSE(cgroup_cpu_quota(dir.path().string()));
}

}  // namespace
}  // namespace tetray
