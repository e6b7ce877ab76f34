// The config is validated whole at create time; every error names the source, line and key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>

#include "adaptor/config/config_parse.hpp"
#include "adaptor/step/trigger.hpp"

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
  EXPECT_TRUE(c.bvh_leaf_size_given);
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
  // Leaves unset: the adaptor chooses per volume (64, or 16 under a clip cap).
  EXPECT_FALSE(r.config->bvh_leaf_size_given);
  EXPECT_EQ(r.config->bvh.build.leaf_size, 64);
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
        BadConfig{"output: {png_compression: 13}\nscenes: [{name: s, field: f, isovalues: [0]}]\n",
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

// Every numeric key at the edges of its range: the values at the limits are accepted (and
// read), the first values beyond them are errors naming the line and the key. `top` is YAML
// placed before the scene, `scene` keys added to the one scene.
struct Edge {
  const char* top;
  const char* scene;
  bool accepted;
  const char* key;  // expected in the message when refused
};

std::string edge_yaml(const Edge& e) {
  return std::string(e.top) + "scenes:\n  - name: s\n    field: f\n" + e.scene;
}

// Test names show the YAML on one line.
void PrintTo(const Edge& e, std::ostream* out) {
  std::string text = std::string(e.top) + e.scene;
  std::replace(text.begin(), text.end(), '\n', ' ');
  *out << text;
}

class ConfigEdges : public ::testing::TestWithParam<Edge> {};

TEST_P(ConfigEdges, LimitsAreInclusiveAndTheNextValueIsRefused) {
  const Edge& e = GetParam();
  const std::string yaml = edge_yaml(e);
  const ParseResult r = parse_config(yaml, "edge.yaml", 3);
  if (e.accepted) {
    EXPECT_TRUE(r.config) << yaml << "\n" << r.error;
    return;
  }
  ASSERT_FALSE(r.config) << yaml;
  EXPECT_NE(r.error.find("edge.yaml:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(e.key), std::string::npos) << r.error;
}

constexpr const char* kIso = "    isovalues: [0]\n";

INSTANTIATE_TEST_SUITE_P(
    Adaptor, ConfigEdges,
    ::testing::Values(
        Edge{"output: {png_compression: -1}\n", kIso, false, "output.png_compression"},
        Edge{"output: {png_compression: 0}\n", kIso, true, ""},
        Edge{"output: {png_compression: 12}\n", kIso, true, ""},
        Edge{"output: {png_compression: 13}\n", kIso, false, "output.png_compression"},
        Edge{"output: {writer_queue_depth: -1}\n", kIso, false, "output.writer_queue_depth"},
        Edge{"output: {writer_queue_depth: 0}\n", kIso, true, ""},
        Edge{"output: {writer_queue_depth: 64}\n", kIso, true, ""},
        Edge{"output: {writer_queue_depth: 65}\n", kIso, false, "output.writer_queue_depth"},
        Edge{"output: {writer_rank: -1}\n", kIso, false, "output.writer_rank"},
        Edge{"output: {writer_rank: 0}\n", kIso, true, ""},
        Edge{"output: {writer_rank: 2}\n", kIso, true, ""},
        Edge{"output: {writer_rank: 3}\n", kIso, false, "output.writer_rank"},
        Edge{"trigger: {every: 0}\n", kIso, false, "trigger.every"},
        Edge{"trigger: {every: 1}\n", kIso, true, ""},
        Edge{"trigger: {every: 1000000000}\n", kIso, true, ""},
        Edge{"trigger: {every: 1000000001}\n", kIso, false, "trigger.every"},
        Edge{"trigger: {every_time: 0}\n", kIso, false, "trigger.every_time"},
        Edge{"trigger: {every_time: -1.0e-300}\n", kIso, false, "trigger.every_time"},
        Edge{"trigger: {every_time: 1.0e-300}\n", kIso, true, ""},
        Edge{"trigger: {every_time: 1.0e308}\n", kIso, true, ""},
        Edge{"trigger: {every_time: .inf}\n", kIso, false, "trigger.every_time"},
        Edge{"trigger: {every_time: .nan}\n", kIso, false, "trigger.every_time"},
        Edge{"bvh: {leaf_size: 0}\n", kIso, false, "bvh.leaf_size"},
        Edge{"bvh: {leaf_size: 1}\n", kIso, true, ""},
        Edge{"bvh: {leaf_size: 64}\n", kIso, true, ""},
        Edge{"bvh: {leaf_size: 65}\n", kIso, false, "bvh.leaf_size"},
        Edge{"bvh: {rebuild_ratio: 0.999}\n", kIso, false, "bvh.rebuild_ratio"},
        Edge{"bvh: {rebuild_ratio: 1}\n", kIso, true, ""},
        Edge{"bvh: {rebuild_ratio: 1.0e6}\n", kIso, true, ""},
        Edge{"bvh: {rebuild_ratio: 1000001}\n", kIso, false, "bvh.rebuild_ratio"},
        Edge{"threads: 0\n", kIso, false, "threads"}, Edge{"threads: 1\n", kIso, true, ""},
        Edge{"threads: 1024\n", kIso, true, ""}, Edge{"threads: 1025\n", kIso, false, "threads"},
        // isovalues: 1 to 16 of them, each within the renderer's field range (+-1e30)
        Edge{"", "    isovalues: []\n", false, "scenes[0].isovalues"},
        Edge{"", "    isovalues: [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15]\n", true,
             ""},
        Edge{"", "    isovalues: [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]\n",
             false, "scenes[0].isovalues"},
        Edge{"", "    isovalues: [-1.0e30, 1.0e30]\n", true, ""},
        Edge{"", "    isovalues: [0, 1.0001e30]\n", false, "scenes[0].isovalues[1]"},
        Edge{"", "    isovalues: [-1.0001e30]\n", false, "scenes[0].isovalues[0]"},
        Edge{"", "    isovalues: [.nan]\n", false, "scenes[0].isovalues[0]"},
        Edge{"", "    isovalues: [0]\n    colors: [[0, 0, 0]]\n", true, ""},
        Edge{"", "    isovalues: [0]\n    colors: [[1, 1, 1]]\n", true, ""},
        Edge{"", "    isovalues: [0]\n    colors: [[-0.001, 0, 0]]\n", false,
             "scenes[0].colors[0]"},
        Edge{"", "    isovalues: [0]\n    colors: [[0, 0, 1.001]]\n", false, "scenes[0].colors[0]"},
        Edge{"", "    isovalues: [0]\n    color_by: g\n    color_range: [-1.0e30, 1.0e30]\n", true,
             ""},
        Edge{"", "    isovalues: [0]\n    color_by: g\n    color_range: [0, 2.0e30]\n", false,
             "scenes[0].color_range[1]"},
        Edge{"", "    isovalues: [0]\n    color_by: g\n    color_range: [1, 1]\n", false,
             "scenes[0].color_range"},
        // camera
        Edge{"", "    isovalues: [0]\n    camera: {fov_deg: 0.999}\n", false,
             "scenes[0].camera.fov_deg"},
        Edge{"", "    isovalues: [0]\n    camera: {fov_deg: 1}\n", true, ""},
        Edge{"", "    isovalues: [0]\n    camera: {fov_deg: 179}\n", true, ""},
        Edge{"", "    isovalues: [0]\n    camera: {fov_deg: 179.001}\n", false,
             "scenes[0].camera.fov_deg"},
        Edge{"", "    isovalues: [0]\n    camera: {fov_deg: .nan}\n", false,
             "scenes[0].camera.fov_deg"},
        Edge{"",
             "    isovalues: [0]\n    camera: {eye: [1.0e12, 0, 0], look_at: [-1.0e12, 0, 0]}\n",
             true, ""},
        Edge{"", "    isovalues: [0]\n    camera: {eye: [1.0001e12, 0, 0], look_at: [0, 0, 0]}\n",
             false, "scenes[0].camera.eye[0]"},
        Edge{"", "    isovalues: [0]\n    camera: {eye: [1, 0, 0], look_at: [0, 0, -1.0001e12]}\n",
             false, "scenes[0].camera.look_at[2]"},
        Edge{"", "    isovalues: [0]\n    camera: {up: [0, 0, 0]}\n", false, "scenes[0].camera.up"},
        Edge{"", "    isovalues: [0]\n    camera: {up: [0, 1.0e-300, 0]}\n", true, ""},
        Edge{"", "    isovalues: [0]\n    camera: {up: [0, 1.0e300, 1.0e300]}\n", true, ""},
        Edge{"", "    isovalues: [0]\n    camera: {view_direction: [0, 1.0e-300, 0]}\n", false,
             "scenes[0].camera"},
        Edge{"", "    isovalues: [0]\n    camera: {eye: [0, 5, 0], look_at: [0, 0, 0]}\n", false,
             "scenes[0].camera"},
        Edge{"",
             "    isovalues: [0]\n    camera: {eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, "
             "1.0e-300, 0]}\n",
             true, ""},
        // image sides: 1 to 16384
        Edge{"", "    isovalues: [0]\n    image: {width: 0}\n", false, "scenes[0].image.width"},
        Edge{"", "    isovalues: [0]\n    image: {width: 1, height: 1}\n", true, ""},
        Edge{"", "    isovalues: [0]\n    image: {width: 16384, height: 16384}\n", true, ""},
        Edge{"", "    isovalues: [0]\n    image: {width: 16385}\n", false, "scenes[0].image.width"},
        Edge{"", "    isovalues: [0]\n    image: {height: 0}\n", false, "scenes[0].image.height"},
        Edge{"", "    isovalues: [0]\n    image: {height: 16385}\n", false,
             "scenes[0].image.height"},
        Edge{"", "    isovalues: [0]\n    background: [0, 0]\n", false, "scenes[0].background"},
        Edge{"", "    isovalues: [0]\n    background: [0, 0, 0]\n", true, ""},
        Edge{"", "    isovalues: [0]\n    background: [1, 1, 1, 1]\n", true, ""},
        Edge{"", "    isovalues: [0]\n    background: [0, 0, 0, 0, 0]\n", false,
             "scenes[0].background"},
        Edge{"", "    isovalues: [0]\n    background: [0, 1.001, 0]\n", false,
             "scenes[0].background"},
        Edge{"", "    isovalues: [0]\n    lights: [{ambient: -0.001}]\n", false,
             "scenes[0].lights[0].ambient"},
        Edge{"", "    isovalues: [0]\n    lights: [{ambient: 0}]\n", true, ""},
        Edge{"", "    isovalues: [0]\n    lights: [{ambient: 1}]\n", true, ""},
        Edge{"", "    isovalues: [0]\n    lights: [{ambient: 1.001}]\n", false,
             "scenes[0].lights[0].ambient"}));

TEST(Config, ImageSidesAtTheLimitsAreRead) {
  const ParseResult r = parse_config(
      "scenes: [{name: s, field: f, isovalues: [0], image: {width: 16384, height: 1}}]", "i.yaml");
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_EQ(r.config->scenes[0].width, 16384);
  EXPECT_EQ(r.config->scenes[0].height, 1);
}

TEST(Config, AHugeImageNamesTheLimitAndItsMemory) {
  const ParseResult r = parse_config(
      "scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n"
      "    image: {width: 100000, height: 100000}\n",
      "huge.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find("huge.yaml:5:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("scenes[0].image.width"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("16384"), std::string::npos) << r.error;
  // 1e10 pixels at 60 bytes each
  EXPECT_NE(r.error.find("100000 x 100000 image would need about 600 GB"), std::string::npos)
      << r.error;
}

std::string scenes_yaml(int count, const std::string& image) {
  std::string yaml = "scenes:\n";
  for (int k = 0; k < count; ++k) {
    yaml += "  - {name: s" + std::to_string(k) + ", field: f, isovalues: [0]" + image + "}\n";
  }
  return yaml;
}

TEST(Config, SceneCountIsLimitedAndTheErrorNamesTheMemory) {
  const ParseResult most = parse_config(scenes_yaml(256, ""), "many.yaml");
  ASSERT_TRUE(most.config) << most.error;
  EXPECT_EQ(most.config->scenes.size(), 256u);
  const ParseResult beyond = parse_config(scenes_yaml(257, ""), "many.yaml");
  ASSERT_FALSE(beyond.config);
  EXPECT_NE(beyond.error.find("many.yaml:2:"), std::string::npos) << beyond.error;
  EXPECT_NE(beyond.error.find("scenes: 257 scenes exceed the limit of 256"), std::string::npos)
      << beyond.error;
  EXPECT_NE(beyond.error.find(" GB"), std::string::npos) << beyond.error;
}

TEST(Config, AllImagesTogetherAreLimited) {
  const std::string largest = ", image: {width: 16384, height: 16384}";
  const ParseResult one = parse_config(scenes_yaml(1, largest), "px.yaml");
  EXPECT_TRUE(one.config) << one.error;
  const ParseResult two = parse_config(scenes_yaml(2, largest), "px.yaml");
  ASSERT_FALSE(two.config);
  EXPECT_NE(two.error.find("px.yaml:2:"), std::string::npos) << two.error;
  EXPECT_NE(two.error.find("536870912 pixels together"), std::string::npos) << two.error;
  EXPECT_NE(two.error.find("about 32.2 GB"), std::string::npos) << two.error;
}

TEST(Config, AConfigOfMegabytesIsRefusedBeforeParsing) {
  std::string yaml = scenes_yaml(1, "");
  const std::string at_limit =
      yaml + "#" + std::string(kMaxConfigBytes - yaml.size() - 2, 'x') + "\n";
  EXPECT_TRUE(parse_config(at_limit, "big.yaml").config);
  const ParseResult beyond = parse_config(at_limit + "\n", "big.yaml");
  ASSERT_FALSE(beyond.config);
  EXPECT_NE(beyond.error.find("big.yaml: the config is 4194305 bytes"), std::string::npos)
      << beyond.error;
}

// Directions are kept as unit vectors, so a camera frame never under- or overflows.
TEST(Config, CameraDirectionsAreStoredAsUnitVectors) {
  const ParseResult r = parse_config(
      "scenes: [{name: s, field: f, isovalues: [0], camera: {up: [0, 0, 1.0e-300], "
      "view_direction: [3.0e300, 0, 0]}}]",
      "dir.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const CameraSpec& cam = r.config->scenes[0].camera;
  EXPECT_EQ(cam.up.z, 1.0);
  EXPECT_EQ(cam.view_direction.x, 1.0);
  EXPECT_EQ(cam.view_direction.y, 0.0);
}

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

// A NaN or infinite time never fires a time trigger and leaves its schedule as it was: the
// next finite time renders as if the bad call had not happened.
TEST(Trigger, NonFiniteTimeSkipsWithoutStoppingTheSchedule) {
  TriggerClock clock(Trigger{1, 0.25});
  EXPECT_FALSE(clock.due(0, std::nan("")));
  ASSERT_TRUE(clock.due(1, 0.0));
  clock.mark_rendered(0.0);
  for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    EXPECT_FALSE(clock.due(2, bad)) << bad;
    clock.mark_rendered(bad);  // even if a caller marks it: the schedule is unchanged
  }
  EXPECT_FALSE(clock.due(3, 0.2));
  EXPECT_TRUE(clock.due(4, 0.25));
  clock.mark_rendered(0.25);
  EXPECT_FALSE(clock.due(5, 0.3));
  EXPECT_TRUE(clock.due(6, 0.5));
}

// A period below the resolution of the time (1e-300 at t = 1, or a denormal whose quotient
// overflows) renders at every later time rather than at none; a repeated time does not render
// twice.
TEST(Trigger, TinyPeriodRendersEveryLaterStep) {
  for (const double period : {1e-300, 5e-324}) {
    TriggerClock clock(Trigger{1, period});
    int rendered = 0;
    for (int k = 0; k < 20; ++k) {
      const double t = 1.0 + 0.1 * (k / 2);  // every time twice
      if (!clock.due(k, t)) continue;
      clock.mark_rendered(t);
      ++rendered;
    }
    EXPECT_EQ(rendered, 10) << period;
  }
}

}  // namespace
}  // namespace tetray::config
