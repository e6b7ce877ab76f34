// The `solver:` section of tetray-minisolver's YAML: mesh, partition, stiff region, time stepping,
// heat, elasticity and CG settings. Unknown keys and bad values are errors naming the key and line.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "minisolver/elasticity.hpp"
#include "minisolver/heat.hpp"
#include "minisolver/mesh.hpp"

namespace minisolver {

enum class MeshKind { box, beam, shell };

struct MeshConfig {
  MeshKind kind = MeshKind::beam;
  std::array<int, 3> cells{24, 6, 6};
  Vec3 lo{0, 0, 0};
  Vec3 hi{4, 1, 1};
  double jitter = 0;  // box only, fraction of the cell size (docs/architecture.md §6 uses 0.15)
  ShellSpec shell;
};

struct HeatConfig {
  HeatSetup setup;  // dt and cg filled from the time and cg sections
  double hot_temperature =
      1;  // held on setup.fixed_faces from the first step; 0 elsewhere at start
};

struct ElasticConfig {
  ElasticSetup setup;  // dt and cg filled from the time and cg sections
  Vec3 body_force{};   // constant, applied from the first step
};

// A second material: the tets whose centroid lies above `above` along `axis` are material 1,
// material 0 with its stiffness (Young's modulus, and the conductivity, the stiffness of the heat
// equation) times `contrast`. Both physics' material tables get the entry.
struct StiffRegion {
  int axis = 0;
  double above = 0;
  double contrast = 1;
};

struct SolverConfig {
  MeshConfig mesh;
  std::optional<StiffRegion> stiff_region;
  std::vector<double> partition_weights;  // per rank; empty: equal shares
  int steps = 50;
  double dt = 0.02;
  std::optional<HeatConfig> heat;
  std::optional<ElasticConfig> elasticity;
};

// False with `error` set ("solver.heat.schem (line 12): unknown key") on any problem. A mesh
// of more than 2^31 - 1 tets, or one whose estimated memory exceeds this machine's, is refused
// with the memory it would need.
bool parse_solver_config(const YAML::Node& solver, SolverConfig& config, std::string& error);

// The whole tetray-minisolver document: a map of exactly `solver` and `tetray`; the solver
// section is parsed into `config` and the tetray section given back as YAML text for the
// adaptor. False with `error` set on any problem, whatever the document holds.
bool parse_run_config(const YAML::Node& root, SolverConfig& config, std::string& tetray_yaml,
                      std::string& error);

}  // namespace minisolver
