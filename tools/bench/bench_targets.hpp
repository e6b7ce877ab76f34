// The targets of issues 3 and 4, checked against one scene's figures. They are defined on the
// 1M-tet scene (n = 56) with 2 threads; the bench reports them for every scene and never fails
// because of them.
#pragma once

#include <string>
#include <vector>

#include "bench_results.hpp"

namespace tetray::bench {

inline constexpr int kTargetScene = 56;

struct TargetCheck {
  std::string name;
  std::string measured;
  std::string target;
  bool pass = false;
};

std::vector<TargetCheck> check_targets(const SceneFigures& figures);

}  // namespace tetray::bench
