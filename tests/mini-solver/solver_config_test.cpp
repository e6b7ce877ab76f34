// The `solver:` section of tetray-minisolver's YAML: a full section parses to the settings it
// spells out, the stiff region adds a scaled material to both physics, and each kind of mistake
// (unknown key, wrong type, impossible value, missing part) is an error naming the key and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "minisolver/partition.hpp"
#include "minisolver/solver_config.hpp"
#include "serial_cube.hpp"

namespace minisolver {
namespace {

const std::string kValid = R"(solver:
  mesh: {kind: box, cells: [4, 3, 2], lo: [-1, -1, -1], hi: [1, 2, 3], jitter: 0.15}
  partition: {weights: [1, 2]}
  stiff_region: {axis: y, above: 0.5, contrast: 1.0e6}
  time: {steps: 7, dt: 0.003}
  heat:
    scheme: backward_euler
    conductivity: 2.5
    capacity: 0.5
    hot_faces: [x_max, z_min]
    hot_temperature: 3.0
  elasticity:
    scheme: central_difference
    young: 210.0
    poisson: 0.25
    density: 7.8
    body_force: [0, -9.8, 0]
    clamped_faces: [y_min]
    allow_unstable: true
  cg: {rtol: 1.0e-9, max_iterations: 123}
)";

// Parses the solver section of `yaml`; the error is empty on success.
std::string parse(const std::string& yaml, SolverConfig& config) {
  std::string error;
  const bool ok = parse_solver_config(YAML::Load(yaml)["solver"], config, error);
  EXPECT_EQ(ok, error.empty()) << error;
  return error;
}

// The 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

// kValid with its first `from` replaced by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = kValid;
  text.replace(text.find(from), from.size(), to);
  return text;
}

// The error for `yaml` starts with "key (line N):", N the line holding `where`, and says `what`.
void expect_error(const std::string& yaml, const std::string& key, const std::string& where,
                  const std::string& what) {
  SolverConfig config;
  const std::string error = parse(yaml, config);
  const std::string expected = key + " (line " + std::to_string(line_of(yaml, where)) + "): ";
  EXPECT_EQ(error.rfind(expected, 0), 0u) << error << "\nexpected it to start with " << expected;
  EXPECT_NE(error.find(what), std::string::npos) << error;
}

TEST(SolverConfig, ValidSectionParsesToTheSettingsItSpellsOut) {
  SolverConfig c;
  ASSERT_EQ(parse(kValid, c), "");
  EXPECT_EQ(c.mesh.kind, MeshKind::box);
  EXPECT_EQ(c.mesh.cells, (std::array<int, 3>{4, 3, 2}));
  EXPECT_EQ(c.mesh.lo, (Vec3{-1, -1, -1}));
  EXPECT_EQ(c.mesh.hi, (Vec3{1, 2, 3}));
  EXPECT_EQ(c.mesh.jitter, 0.15);
  EXPECT_EQ(c.partition_weights, (std::vector<double>{1, 2}));
  EXPECT_EQ(c.steps, 7);
  EXPECT_EQ(c.dt, 0.003);
  ASSERT_TRUE(c.heat && c.elasticity);

  const HeatSetup& heat = c.heat->setup;
  EXPECT_EQ(heat.scheme, ThetaScheme::backward_euler);
  EXPECT_EQ(heat.materials.front().conductivity, 2.5);
  EXPECT_EQ(heat.materials.front().capacity, 0.5);
  EXPECT_EQ(heat.fixed_faces, x_max | z_min);
  EXPECT_EQ(c.heat->hot_temperature, 3.0);

  const ElasticSetup& elastic = c.elasticity->setup;
  EXPECT_EQ(elastic.scheme, ElasticScheme::central_difference);
  EXPECT_EQ(elastic.materials.front().young, 210.0);
  EXPECT_EQ(elastic.materials.front().poisson, 0.25);
  EXPECT_EQ(elastic.materials.front().density, 7.8);
  EXPECT_EQ(c.elasticity->body_force, (Vec3{0, -9.8, 0}));
  EXPECT_EQ(elastic.fixed_faces, y_min);
  EXPECT_TRUE(elastic.allow_unstable);

  // The time and cg sections reach both physics.
  for (const auto& [dt, cg] : {std::pair{heat.dt, heat.cg}, std::pair{elastic.dt, elastic.cg}}) {
    EXPECT_EQ(dt, c.dt);
    EXPECT_EQ(cg.rtol, 1e-9);
    EXPECT_EQ(cg.max_iterations, 123);
  }
}

TEST(SolverConfig, StiffRegionAddsMaterialZeroWithItsStiffnessScaled) {
  SolverConfig c;
  ASSERT_EQ(parse(kValid, c), "");
  ASSERT_TRUE(c.stiff_region);
  EXPECT_EQ(c.stiff_region->axis, 1);
  EXPECT_EQ(c.stiff_region->above, 0.5);
  const double contrast = c.stiff_region->contrast;
  EXPECT_EQ(contrast, 1e6);

  const auto& heat = c.heat->setup.materials;
  ASSERT_EQ(heat.size(), 2u);
  EXPECT_EQ(heat[1].conductivity, contrast * heat[0].conductivity);
  EXPECT_EQ(heat[1].capacity, heat[0].capacity);

  const auto& elastic = c.elasticity->setup.materials;
  ASSERT_EQ(elastic.size(), 2u);
  EXPECT_EQ(elastic[1].young, contrast * elastic[0].young);
  EXPECT_EQ(elastic[1].poisson, elastic[0].poisson);
  EXPECT_EQ(elastic[1].density, elastic[0].density);
}

TEST(SolverConfig, WithoutStiffRegionEachPhysicsHasOneMaterial) {
  SolverConfig c;
  const std::string yaml = edited("  stiff_region: {axis: y, above: 0.5, contrast: 1.0e6}\n", "");
  ASSERT_EQ(parse(yaml, c), "");
  EXPECT_FALSE(c.stiff_region);
  EXPECT_EQ(c.heat->setup.materials.size(), 1u);
  EXPECT_EQ(c.elasticity->setup.materials.size(), 1u);
}

TEST(SolverConfig, UnknownKeysAreNamedWithTheirLine) {
  expect_error(edited("scheme: backward_euler", "schem: backward_euler"), "solver.heat.schem",
               "schem:", "unknown key");
  expect_error(edited("  cg:", "  gc:"), "solver.gc", "gc:", "unknown key");
  expect_error(edited("contrast: 1.0e6", "ratio: 1.0e6"), "solver.stiff_region.ratio",
               "ratio:", "unknown key");
}

TEST(SolverConfig, WrongTypesAreNamedWithTheirLine) {
  expect_error(edited("steps: 7", "steps: many"), "solver.time.steps", "many",
               "expected an integer");
  expect_error(edited("young: 210.0", "young: [210]"), "solver.elasticity.young", "[210]",
               "expected a number");
  expect_error(edited("cells: [4, 3, 2]", "cells: [4, 3]"), "solver.mesh.cells", "[4, 3]",
               "expected a list of 3");
  expect_error(edited("above: 0.5", "above: high"), "solver.stiff_region.above", "high",
               "expected a number");
  expect_error(edited("allow_unstable: true", "allow_unstable: maybe"),
               "solver.elasticity.allow_unstable", "maybe", "expected true or false");
}

TEST(SolverConfig, ImpossibleValuesAreNamedWithTheirLine) {
  expect_error(edited("dt: 0.003", "dt: -0.003"), "solver.time.dt", "-0.003", "must be > 0");
  expect_error(edited("poisson: 0.25", "poisson: 0.5"), "solver.elasticity.poisson", "poisson: 0.5",
               "must lie in (-1, 0.5)");
  expect_error(edited("density: 7.8", "density: 0"), "solver.elasticity.density", "density: 0",
               "must be > 0");
  expect_error(edited("scheme: central_difference", "scheme: leapfrog"), "solver.elasticity.scheme",
               "leapfrog", "'leapfrog' is not one of");
  expect_error(edited("contrast: 1.0e6", "contrast: -1"), "solver.stiff_region.contrast",
               "contrast: -1", "must be > 0");
  expect_error(edited("axis: y", "axis: w"), "solver.stiff_region.axis", "axis: w",
               "is not one of x, y, z");
}

TEST(SolverConfig, AStiffRegionMustSayWhereAndHowStiff) {
  expect_error(edited("axis: y, above: 0.5, ", "axis: y, "), "solver.stiff_region.above",
               "stiff_region:", "missing");
}

// Sizes that overflow int arithmetic, or a mesh no machine holds, are refused with the memory
// they would need before anything is allocated (a mesh is built whole on every rank).
TEST(SolverConfig, MeshesBeyondTheLimitsAreRefusedWithTheirMemory) {
  expect_error(edited("cells: [4, 3, 2]", "cells: [2147483647, 1, 1]"), "solver.mesh.cells",
               "2147483647", "12884901882 tets exceed the limit of 2147483647");
  expect_error(edited("cells: [4, 3, 2]", "cells: [2147483647, 2147483647, 2147483647]"),
               "solver.mesh.cells", "2147483647", "tets exceed the limit");
  expect_error(edited("cells: [4, 3, 2]", "cells: [1000, 1000, 1000]"), "solver.mesh.cells", "1000",
               "it would need about 2.7e+03 GB");
  // At the tet limit (357913941 hexes, 6 tets each: 2147483646 tets) the figure is the memory.
  expect_error(edited("cells: [4, 3, 2]", "cells: [357913941, 1, 1]"), "solver.mesh.cells",
               "357913941", "does not fit this machine's");
  expect_error(edited("cells: [4, 3, 2]", "cells: [0, 1, 1]"), "solver.mesh.cells", "[0, 1, 1]",
               "must be >= 1");
  SolverConfig c;
  EXPECT_EQ(parse(edited("cells: [4, 3, 2]", "cells: [1, 1, 1]"), c), "");
  EXPECT_EQ(grid_counts(c.mesh.cells).tets, 6u);
}

TEST(SolverConfig, PartitionWeightsMustBeFiniteAndNotNegative) {
  expect_error(edited("weights: [1, 2]", "weights: [1, -2]"), "solver.partition.weights", "-2",
               "finite number >= 0");
  expect_error(edited("weights: [1, 2]", "weights: [1, .inf]"), "solver.partition.weights", ".inf",
               "finite number >= 0");
  expect_error(edited("weights: [1, 2]", "weights: [0, 0]"), "solver.partition.weights", "[0, 0]",
               "at least one weight > 0");
  SolverConfig c;
  ASSERT_EQ(parse(edited("weights: [1, 2]", "weights: [0, 1]"), c), "");
  EXPECT_EQ(c.partition_weights, (std::vector<double>{0, 1}));
}

TEST(SolverConfig, KeysThatAreListsOrMapsAreErrorsNotExceptions) {
  expect_error(edited("  time: {steps: 7, dt: 0.003}", "  time: {[7, 8]: 7, dt: 0.003}"),
               "solver.time", "[7, 8]", "a key must be a name");
}

// The whole document: whatever it holds, parse_run_config returns an error, never throws.
TEST(SolverConfig, RunDocumentsOfAnyShapeGiveErrors) {
  const std::pair<const char*, const char*> cases[] = {
      {"[1, 2, 3]", "(document) (line 1): expected a map"},
      {"just a scalar", "(document) (line 1): expected a map"},
      {"", "(document): expected a map"},
      {"{[1, 2]: 3, tetray: {}}", "(document) (line 1): a key must be a name"},
      {"solver: {}\nother: 1\ntetray: {}", "other (line 2): unknown key"},
      {"solver: {time: {steps: 1}, heat: {}}", "tetray: missing section"},
      {"tetray: {}", "solver: missing section"},
      {"solver: [1]\ntetray: {}", "solver (line 1): expected a map"},
  };
  for (const auto& [yaml, expected] : cases) {
    SolverConfig config;
    std::string tetray_yaml, error;
    EXPECT_FALSE(parse_run_config(YAML::Load(yaml), config, tetray_yaml, error)) << yaml;
    EXPECT_EQ(error.rfind(expected, 0), 0u) << yaml << ": " << error;
  }
  SolverConfig config;
  std::string tetray_yaml, error;
  ASSERT_TRUE(
      parse_run_config(YAML::Load(kValid + "tetray: {scenes: []}\n"), config, tetray_yaml, error))
      << error;
  EXPECT_EQ(YAML::Load(tetray_yaml)["scenes"].size(), 0u);
  EXPECT_EQ(config.steps, 7);
}

// Weights the config refuses can still reach partition_rcb from code: a negative weight once
// cut outside the tet list (a heap overflow). Every tet gets a part in [0, parts).
TEST(SolverConfig, PartitionOfRefusedWeightsStaysInsideTheMesh) {
  const Mesh mesh = testing::unit_cube(3);
  const std::vector<std::vector<double>> cases{
      {-1, 3, 1}, {2, 1, -2}, {std::nan(""), 1, 1}, {1, 2}};
  for (const auto& weights : cases) {
    const auto part = partition_rcb(mesh, 3, weights);
    ASSERT_EQ(part.size(), mesh.tet_count());
    for (const auto p : part) EXPECT_TRUE(p >= 0 && p < 3) << p;
  }
}

// Every shipped config with a solver section (the README's demo, the examples) keeps one this
// parser accepts.
TEST(SolverConfig, ShippedSolverConfigsParse) {
  namespace fs = std::filesystem;
  std::vector<std::string> parsed;
  for (const auto& entry :
       fs::recursive_directory_iterator(fs::path(TETRAY_SOURCE_DIR) / "configs")) {
    if (entry.path().extension() != ".yaml") continue;
    const YAML::Node root = YAML::LoadFile(entry.path().string());
    if (!root["solver"]) continue;
    SolverConfig c;
    std::string error;
    EXPECT_TRUE(parse_solver_config(root["solver"], c, error)) << entry.path() << ": " << error;
    parsed.push_back(entry.path().filename().string());
  }
  EXPECT_NE(std::find(parsed.begin(), parsed.end(), "demo.yaml"), parsed.end());
}

}  // namespace
}  // namespace minisolver
