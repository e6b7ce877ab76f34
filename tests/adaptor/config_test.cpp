// The config is validated whole at create time; every error names the source, line and key.
#include <gtest/gtest.h>

#include "config_parse.hpp"
#include "trigger.hpp"

namespace tetray::config {
namespace {

const char* kFull = R"(output:
  directory: out/x
  formats: [png]
  cinema: false
  png_compression: 6
  writer_queue_depth: 0
  quiet: true
trigger: {every: 5}
nonfinite: skip_tets
bvh: {builder: sah, leaf_size: 4, rebuild_ratio: 2.5}
scenes:
  - name: a
    field: temperature
    isovalues: [0.3, 0.6]
    colors: [[1, 0, 0], [0, 1, 0]]
    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 30}
    image: {width: 320, height: 200}
    background: [0.1, 0.2, 0.3]
    lights: [{type: headlight, ambient: 0.2}]
  - name: b
    field: temperature
    isovalues: [0]
    color_by: stress
    colormap: coolwarm
    color_range: [-1, 2]
    camera: {auto_fit: true, view_direction: [0, 0, 1]}
    trigger: {every_time: 0.25}
)";

TEST(Config, ReadsEveryKey) {
  const ParseResult r = parse_config(kFull, "full.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const Config& c = *r.config;
  EXPECT_EQ(c.output.directory, "out/x");
  EXPECT_FALSE(c.output.exr);
  EXPECT_TRUE(c.output.png);
  EXPECT_FALSE(c.output.cinema);
  EXPECT_EQ(c.output.png_compression, 6);
  EXPECT_EQ(c.output.queue_depth, 0);
  EXPECT_EQ(c.nonfinite, render::NonFinitePolicy::skip_tets);
  EXPECT_EQ(c.bvh.build.builder, render::BvhBuilder::sah);
  EXPECT_EQ(c.bvh.build.leaf_size, 4);
  EXPECT_EQ(c.bvh.rebuild_ratio, 2.5);
  ASSERT_EQ(c.scenes.size(), 2u);
  const Scene& a = c.scenes[0];
  EXPECT_EQ(a.trigger.every_steps, 5);
  ASSERT_EQ(a.surfaces.size(), 2u);
  EXPECT_FLOAT_EQ(a.surfaces[1].value, 0.6f);
  EXPECT_EQ(a.surfaces[1].color.g, 1.0f);
  EXPECT_FALSE(a.camera.auto_fit);
  EXPECT_EQ(a.camera.fixed.eye.z, 3.2);
  EXPECT_EQ(a.camera.fixed.fov_deg, 30);
  EXPECT_EQ(a.width, 320);
  EXPECT_EQ(a.height, 200);
  EXPECT_FLOAT_EQ(a.background[2], 0.3f);
  EXPECT_FLOAT_EQ(a.background[3], 1.0f);
  EXPECT_FLOAT_EQ(a.ambient, 0.2f);
  const Scene& b = c.scenes[1];
  EXPECT_EQ(b.color_by, "stress");
  EXPECT_EQ(b.colormap_name, "coolwarm");
  EXPECT_FALSE(b.color_range.automatic);
  EXPECT_FLOAT_EQ(b.color_range.hi, 2.0f);
  EXPECT_TRUE(b.camera.auto_fit);
  EXPECT_EQ(b.camera.view_direction.z, 1.0);
  EXPECT_EQ(b.trigger.every_time, 0.25);
}

TEST(Config, DefaultsNeedOnlyNameFieldIsovalues) {
  const ParseResult r = parse_config("scenes: [{name: s, field: f, isovalues: [0]}]", "min.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const Scene& s = r.config->scenes[0];
  EXPECT_TRUE(s.camera.auto_fit);
  EXPECT_EQ(s.trigger.every_steps, 1);
  EXPECT_TRUE(r.config->output.exr && r.config->output.png && r.config->output.cinema);
  EXPECT_EQ(r.config->output.png_compression, 1);
  EXPECT_EQ(r.config->output.writer_rank, 0);
  EXPECT_FALSE(r.config->output.per_rank_images);
  EXPECT_TRUE(s.color_by.empty());
}

TEST(Config, WriterRankMustBeARankOfTheCommunicator) {
  const auto yaml = [](int rank) {
    return "scenes: [{name: s, field: f, isovalues: [0]}]\noutput:\n  per_rank_images: true\n"
           "  writer_rank: " +
           std::to_string(rank) + "\n";
  };
  const ParseResult last = parse_config(yaml(2), "ranks.yaml", 3);
  ASSERT_TRUE(last.config) << last.error;
  EXPECT_EQ(last.config->output.writer_rank, 2);
  EXPECT_TRUE(last.config->output.per_rank_images);
  const ParseResult beyond = parse_config(yaml(3), "ranks.yaml", 3);
  ASSERT_FALSE(beyond.config);
  EXPECT_NE(beyond.error.find("ranks.yaml:4:"), std::string::npos) << beyond.error;
  EXPECT_NE(beyond.error.find("output.writer_rank"), std::string::npos) << beyond.error;
  EXPECT_NE(beyond.error.find("3 rank(s)"), std::string::npos) << beyond.error;
}

struct BadConfig {
  const char* yaml;
  const char* where;  // "file:line" expected in the message
  const char* key;    // the key path expected in the message
};

class ConfigErrors : public ::testing::TestWithParam<BadConfig> {};

TEST_P(ConfigErrors, NameFileLineAndKey) {
  const BadConfig& bad = GetParam();
  const ParseResult r = parse_config(bad.yaml, "bad.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find(bad.where), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(bad.key), std::string::npos) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Adaptor, ConfigErrors,
    ::testing::Values(
        // unknown key
        BadConfig{"scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n    colour: red\n",
                  "bad.yaml:5:", "scenes[0].colour"},
        BadConfig{"outptu: {}\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:1:", "outptu"},
        // wrong type
        BadConfig{"trigger: {every: five}\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:1:", "trigger.every"},
        BadConfig{"scenes:\n  - name: s\n    field: f\n    isovalues: 0.5\n",
                  "bad.yaml:4:", "scenes[0].isovalues"},
        // impossible values
        BadConfig{"scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n"
                  "    image: {width: -3}\n",
                  "bad.yaml:5:", "scenes[0].image.width"},
        BadConfig{"output: {png_compression: 12}\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:1:", "output.png_compression"},
        BadConfig{"output: {writer_rank: -1}\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:1:", "output.writer_rank"},
        BadConfig{"output:\n  per_rank_images: 2\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:2:", "output.per_rank_images"},
        BadConfig{"trigger: {every: 0}\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:1:", "trigger.every"},
        BadConfig{"scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n"
                  "    color_by: g\n    colormap: rainbow\n",
                  "bad.yaml:6:", "scenes[0].colormap"},
        BadConfig{"scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n"
                  "    camera: {eye: [0, 0, 1], look_at: [0, 0, 1]}\n",
                  "bad.yaml:5:", "scenes[0].camera"},
        BadConfig{"scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n"
                  "    lights: [{type: spot}]\n",
                  "bad.yaml:5:", "scenes[0].lights[0].type"},
        BadConfig{"scenes:\n  - {name: s, field: f, isovalues: [0]}\n"
                  "  - {name: s, field: g, isovalues: [1]}\n",
                  "bad.yaml:3:", "scenes[1].name"},
        BadConfig{"scenes:\n  - {name: s, field: f, isovalues: [0], trigger: {every: 2, "
                  "every_time: 0.5}}\n",
                  "bad.yaml:2:", "scenes[0].trigger"},
        BadConfig{"nonfinite: ignore\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
                  "bad.yaml:1:", "nonfinite"},
        BadConfig{"scenes:\n  - name: s\n    field: f\n", "bad.yaml:2:", "scenes[0].isovalues"},
        BadConfig{"scenes: [{name: s, field: f, isovalues: [0]}\n", "bad.yaml:", "YAML syntax"}));

TEST(Config, MissingFileIsNamed) {
  const ParseResult r = load_config_file("/nonexistent/tetray.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find("/nonexistent/tetray.yaml"), std::string::npos) << r.error;
}

TEST(Trigger, EveryNSteps) {
  const TriggerClock clock(Trigger{3, 0});
  for (int step = -6; step <= 9; ++step) EXPECT_EQ(clock.due(step, 0), step % 3 == 0) << step;
}

TEST(Trigger, EveryTimeRendersOncePerPeriod) {
  TriggerClock clock(Trigger{1, 0.25});
  // Steps of 0.1: the first call renders, then the first call at or past each multiple of 0.25.
  std::vector<int> rendered;
  for (int k = 0; k <= 12; ++k) {
    const double t = 0.1 * k;
    if (!clock.due(k, t)) continue;
    clock.mark_rendered(t);
    rendered.push_back(k);
  }
  EXPECT_EQ(rendered, (std::vector<int>{0, 3, 5, 8, 10}));
}

}  // namespace
}  // namespace tetray::config
