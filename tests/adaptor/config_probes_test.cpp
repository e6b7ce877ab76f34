// The probes key: points and lines expand into one list in config order; mistakes name the key.
#include <gtest/gtest.h>

#include "adaptor/config/config_parse.hpp"

namespace tetray::config {
namespace {

const std::string kScene = "scenes: [{name: a, field: f, isovalues: [0]}]\n";

ParseResult parse(const std::string& probes) {
  return parse_config(kScene + "probes:\n" + probes, "probes.yaml", 1);
}

TEST(ConfigProbes, PointsThenLineSamples) {
  const ParseResult r = parse(
      "  - name: p\n"
      "    fields: [f, g]\n"
      "    points: [[1, 2, 3]]\n"
      "    lines: [{from: [0, 0, 0], to: [1, 0, -2], samples: 3}]\n");
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.config->probes.size(), 1u);
  const ProbeSet& set = r.config->probes[0];
  EXPECT_EQ(set.name, "p");
  EXPECT_EQ(set.fields, (std::vector<std::string>{"f", "g"}));
  ASSERT_EQ(set.points.size(), 4u);
  EXPECT_EQ(set.points[0].z, 3);
  EXPECT_EQ(set.points[2].x, 0.5);
  EXPECT_EQ(set.points[2].z, -1);
  EXPECT_EQ(set.points[3].z, -2);
}

TEST(ConfigProbes, MistakesNameTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"  - {name: p, fields: [f]}\n", "probes[0]: give points or lines"},
      {"  - {name: p, points: [[0, 0, 0]]}\n", "probes[0].fields: missing"},
      {"  - {name: p, fields: [], points: [[0, 0, 0]]}\n", "name at least one field"},
      {"  - {name: 'a/b', fields: [f], points: [[0, 0, 0]]}\n", "probes[0].name"},
      {"  - {name: p, fields: [f], points: [[0, 0]]}\n", "probes[0].points[0]"},
      {"  - {name: p, fields: [f], lines: [{from: [0, 0, 0], to: [1, 1, 1], samples: 1}]}\n",
       "probes[0].lines[0].samples"},
      {"  - {name: p, fields: [f], points: [[0, 0, 0]], every: 2}\n", "every"},
      {"  - {name: p, fields: [f], points: [[0, 0, 0]]}\n  - {name: p, fields: [f], points: "
       "[[0, 0, 0]]}\n",
       "duplicate probe set name"},
  };
  for (const auto& [yaml, expected] : cases) {
    const ParseResult r = parse(yaml);
    EXPECT_NE(r.error.find(expected), std::string::npos) << yaml << " gave: " << r.error;
    EXPECT_NE(r.error.find("probes.yaml:"), std::string::npos) << r.error;
  }
}

}  // namespace
}  // namespace tetray::config
