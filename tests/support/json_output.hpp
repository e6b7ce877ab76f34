// For the tests of tools that write JSON (--json FILE): runs the command with FILE appended and
// returns the parsed file, failing the test when the command or the parse fails.
#pragma once

#include <gtest/gtest.h>
#include <json/json.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace tetray::testing {

inline Json::Value run_for_json(const std::string& command, const std::string& file_name) {
  const auto path = std::filesystem::temp_directory_path() / file_name;
  std::filesystem::remove(path);
  const std::string full = command + " --json " + path.string() + " > /dev/null";
  EXPECT_EQ(std::system(full.c_str()), 0) << full;
  std::ifstream file(path);
  Json::Value root;
  Json::CharReaderBuilder reader;
  std::string errors;
  EXPECT_TRUE(Json::parseFromStream(reader, file, &root, &errors)) << errors;
  return root;
}

}  // namespace tetray::testing
