// The example configs shipped for users parse without error.
#include <gtest/gtest.h>

#include "adaptor/config/config_parse.hpp"

namespace tetray::config {
namespace {

TEST(ConfigExamples, AllParse) {
  for (const char* name : {"adaptor_minimal.yaml", "adaptor_full.yaml", "gyroid_replay.yaml",
                           "gyroid_modalities.yaml"}) {
    const ParseResult r = load_config_file(std::string(TETRAY_EXAMPLES_DIR) + "/" + name);
    EXPECT_TRUE(r.config) << r.error;
  }
}

}  // namespace
}  // namespace tetray::config
