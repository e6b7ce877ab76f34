#include "minisolver/solver_config.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace minisolver {
namespace {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& what) {
  // An empty document has no position.
  const YAML::Mark mark = node.Mark();
  const std::string line = mark.is_null() ? "" : " (line " + std::to_string(mark.line + 1) + ")";
  throw ConfigError(key + line + ": " + what);
}

// A map key as text; a key that is a list or a map is an error (YAML allows it, no key here is).
std::string key_name(const YAML::Node& name, const std::string& key) {
  if (!name.IsScalar()) fail(name, key, "a key must be a name, not a list or a map");
  return name.Scalar();
}

void allow_keys(const YAML::Node& node, const std::string& key,
                std::initializer_list<std::string> allowed) {
  if (!node.IsMap()) fail(node, key, "expected a map");
  for (const auto& entry : node) {
    const std::string name = key_name(entry.first, key);
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      fail(entry.first, key + "." + name, "unknown key");
  }
}

template <class T>
T scalar(const YAML::Node& node, const std::string& key, const char* what) {
  try {
    if (node.IsScalar()) return node.as<T>();
  } catch (const YAML::Exception&) {
  }
  fail(node, key, std::string("expected ") + what);
}

double positive(const YAML::Node& node, const std::string& key) {
  const auto v = scalar<double>(node, key, "a number");
  if (!(v > 0)) fail(node, key, "must be > 0");
  return v;
}

template <std::size_t N, class T>
std::array<T, N> fixed_list(const YAML::Node& node, const std::string& key, const char* what) {
  if (!node.IsSequence() || node.size() != N)
    fail(node, key, "expected a list of " + std::to_string(N) + " " + what);
  std::array<T, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = scalar<T>(node[i], key, what);
  return out;
}

std::string choice(const YAML::Node& node, const std::string& key,
                   std::initializer_list<std::string> options) {
  const auto v = scalar<std::string>(node, key, "a string");
  if (std::find(options.begin(), options.end(), v) != options.end()) return v;
  std::string list;
  for (const auto& o : options) list += (list.empty() ? "" : ", ") + o;
  fail(node, key, "'" + v + "' is not one of " + list);
}

std::uint8_t faces(const YAML::Node& node, const std::string& key) {
  if (!node.IsSequence()) fail(node, key, "expected a list of faces");
  static const std::initializer_list<std::string> kNames{"x_min", "x_max", "y_min",
                                                         "y_max", "z_min", "z_max"};
  std::uint8_t bits = 0;
  for (const auto& item : node) {
    const std::string name = choice(item, key, kNames);
    bits |= static_cast<std::uint8_t>(
        1 << (std::find(kNames.begin(), kNames.end(), name) - kNames.begin()));
  }
  return bits;
}

// A rough figure of the whole run's memory per hexahedron of the grid, every rank building the
// whole mesh: 6 tets of 4 int64 ids and a material (216 B), a point of coordinates and face bits
// (25 B), the heat matrix (about 15 entries of 12 B per row: 180 B), the elasticity matrix (3
// rows of about 45 entries: 1620 B) and some 20 vectors per degree of freedom (640 B).
constexpr double kBytesPerHex = 2700;
// The renderer and the solver's partition index tets with 32 bits.
constexpr std::uint64_t kMaxTets = std::numeric_limits<std::int32_t>::max();

std::string gigabytes(double bytes) {
  std::ostringstream out;
  out.precision(3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size)
                                    : std::numeric_limits<double>::infinity();
}

// Refuses a grid the run could not hold, before anything is allocated.
void check_mesh_size(const YAML::Node& node, const std::string& key, std::array<int, 3> cells) {
  const GridCounts counts = grid_counts(cells);
  const double hexes = static_cast<double>(counts.tets / 6);
  const std::string needs = "; it would need about " + gigabytes(hexes * kBytesPerHex) +
                            " (about " + std::to_string(static_cast<int>(kBytesPerHex)) +
                            " bytes per cell)";
  if (counts.tets > kMaxTets) {
    fail(node, key,
         std::to_string(counts.tets) + " tets exceed the limit of " + std::to_string(kMaxTets) +
             " (32-bit tet indices)" + needs);
  }
  const double memory = physical_memory_bytes();
  if (hexes * kBytesPerHex > memory) {
    fail(node, key, "the mesh does not fit this machine's " + gigabytes(memory) + needs);
  }
}

void parse_mesh(const YAML::Node& node, MeshConfig& mesh) {
  const std::string key = "solver.mesh";
  allow_keys(node, key, {"kind", "cells", "lo", "hi", "jitter", "inner_radius", "outer_radius"});
  if (node["kind"]) {
    const std::string kind = choice(node["kind"], key + ".kind", {"box", "beam", "shell"});
    mesh.kind = kind == "box" ? MeshKind::box : (kind == "beam" ? MeshKind::beam : MeshKind::shell);
  }
  if (node["cells"]) {
    mesh.cells = fixed_list<3, int>(node["cells"], key + ".cells", "integers");
    if (*std::min_element(mesh.cells.begin(), mesh.cells.end()) < 1)
      fail(node["cells"], key + ".cells", "must be >= 1");
    check_mesh_size(node["cells"], key + ".cells", mesh.cells);
  }
  if (node["lo"]) mesh.lo = fixed_list<3, double>(node["lo"], key + ".lo", "numbers");
  if (node["hi"]) mesh.hi = fixed_list<3, double>(node["hi"], key + ".hi", "numbers");
  for (int a = 0; a < 3; ++a)
    if (!(mesh.hi[a] > mesh.lo[a])) fail(node, key, "hi must exceed lo on every axis");
  if (node["jitter"]) mesh.jitter = scalar<double>(node["jitter"], key + ".jitter", "a number");
  if (node["inner_radius"])
    mesh.shell.inner_radius = positive(node["inner_radius"], key + ".inner_radius");
  if (node["outer_radius"])
    mesh.shell.outer_radius = positive(node["outer_radius"], key + ".outer_radius");
  if (mesh.shell.outer_radius <= mesh.shell.inner_radius)
    fail(node, key, "outer_radius must exceed inner_radius");
}

void parse_heat(const YAML::Node& node, HeatConfig& heat) {
  const std::string key = "solver.heat";
  allow_keys(node, key, {"scheme", "conductivity", "capacity", "hot_faces", "hot_temperature"});
  HeatMaterial& m = heat.setup.materials.at(0);
  if (node["scheme"])
    heat.setup.scheme = choice(node["scheme"], key + ".scheme",
                               {"backward_euler", "crank_nicolson"}) == "backward_euler"
                            ? ThetaScheme::backward_euler
                            : ThetaScheme::crank_nicolson;
  if (node["conductivity"]) m.conductivity = positive(node["conductivity"], key + ".conductivity");
  if (node["capacity"]) m.capacity = positive(node["capacity"], key + ".capacity");
  heat.setup.fixed_faces = x_min;
  if (node["hot_faces"]) heat.setup.fixed_faces = faces(node["hot_faces"], key + ".hot_faces");
  if (node["hot_temperature"])
    heat.hot_temperature =
        scalar<double>(node["hot_temperature"], key + ".hot_temperature", "a number");
}

void parse_elasticity(const YAML::Node& node, ElasticConfig& elastic) {
  const std::string key = "solver.elasticity";
  allow_keys(
      node, key,
      {"scheme", "young", "poisson", "density", "body_force", "clamped_faces", "allow_unstable"});
  ElasticMaterial& m = elastic.setup.materials.at(0);
  if (node["scheme"])
    elastic.setup.scheme =
        choice(node["scheme"], key + ".scheme", {"newmark", "central_difference"}) == "newmark"
            ? ElasticScheme::newmark
            : ElasticScheme::central_difference;
  if (node["young"]) m.young = positive(node["young"], key + ".young");
  if (node["poisson"]) {
    m.poisson = scalar<double>(node["poisson"], key + ".poisson", "a number");
    if (!(m.poisson > -1 && m.poisson < 0.5))
      fail(node["poisson"], key + ".poisson", "must lie in (-1, 0.5)");
  }
  if (node["density"]) m.density = positive(node["density"], key + ".density");
  if (node["body_force"])
    elastic.body_force = fixed_list<3, double>(node["body_force"], key + ".body_force", "numbers");
  elastic.setup.fixed_faces = x_min;
  if (node["clamped_faces"])
    elastic.setup.fixed_faces = faces(node["clamped_faces"], key + ".clamped_faces");
  if (node["allow_unstable"])
    elastic.setup.allow_unstable =
        scalar<bool>(node["allow_unstable"], key + ".allow_unstable", "true or false");
}

void parse_time(const YAML::Node& node, SolverConfig& config) {
  allow_keys(node, "solver.time", {"steps", "dt"});
  if (node["steps"]) {
    config.steps = scalar<int>(node["steps"], "solver.time.steps", "an integer");
    if (config.steps < 0) fail(node["steps"], "solver.time.steps", "must be >= 0");
  }
  if (node["dt"]) config.dt = positive(node["dt"], "solver.time.dt");
}

StiffRegion parse_stiff_region(const YAML::Node& node) {
  const std::string key = "solver.stiff_region";
  allow_keys(node, key, {"axis", "above", "contrast"});
  for (const char* required : {"axis", "above", "contrast"})
    if (!node[required]) fail(node, key + "." + required, "missing");
  StiffRegion region;
  region.axis = choice(node["axis"], key + ".axis", {"x", "y", "z"})[0] - 'x';
  region.above = scalar<double>(node["above"], key + ".above", "a number");
  region.contrast = positive(node["contrast"], key + ".contrast");
  return region;
}

// Material 1 of both physics: material 0 with its stiffness scaled by the contrast.
void add_stiff_material(SolverConfig& config) {
  const double contrast = config.stiff_region->contrast;
  if (config.heat) {
    auto& materials = config.heat->setup.materials;
    materials.push_back(materials.front());
    materials.back().conductivity *= contrast;
  }
  if (config.elasticity) {
    auto& materials = config.elasticity->setup.materials;
    materials.push_back(materials.front());
    materials.back().young *= contrast;
  }
}

CgSettings parse_cg(const YAML::Node& node) {
  allow_keys(node, "solver.cg", {"rtol", "max_iterations"});
  CgSettings cg;
  if (node["rtol"]) cg.rtol = positive(node["rtol"], "solver.cg.rtol");
  if (node["max_iterations"])
    cg.max_iterations =
        scalar<int>(node["max_iterations"], "solver.cg.max_iterations", "an integer");
  return cg;
}

void parse(const YAML::Node& solver, SolverConfig& config) {
  allow_keys(solver, "solver",
             {"mesh", "partition", "stiff_region", "time", "heat", "elasticity", "cg"});
  if (solver["mesh"]) parse_mesh(solver["mesh"], config.mesh);
  if (solver["stiff_region"]) config.stiff_region = parse_stiff_region(solver["stiff_region"]);
  if (const YAML::Node p = solver["partition"]) {
    allow_keys(p, "solver.partition", {"weights"});
    if (!p["weights"].IsSequence())
      fail(p, "solver.partition.weights", "expected a list of numbers");
    for (const auto& w : p["weights"]) {
      const double weight = scalar<double>(w, "solver.partition.weights", "a number");
      if (!(weight >= 0 && std::isfinite(weight)))
        fail(w, "solver.partition.weights", "a weight must be a finite number >= 0");
      config.partition_weights.push_back(weight);
    }
    const auto& weights = config.partition_weights;
    if (std::none_of(weights.begin(), weights.end(), [](double w) { return w > 0; }))
      fail(p["weights"], "solver.partition.weights", "give at least one weight > 0");
  }
  if (solver["time"]) parse_time(solver["time"], config);
  const CgSettings cg = solver["cg"] ? parse_cg(solver["cg"]) : CgSettings{};
  if (solver["heat"]) {
    parse_heat(solver["heat"], config.heat.emplace());
    config.heat->setup.dt = config.dt;
    config.heat->setup.cg = cg;
  }
  if (solver["elasticity"]) {
    parse_elasticity(solver["elasticity"], config.elasticity.emplace());
    config.elasticity->setup.dt = config.dt;
    config.elasticity->setup.cg = cg;
  }
  if (!config.heat && !config.elasticity) fail(solver, "solver", "needs heat, elasticity or both");
  if (config.stiff_region) add_stiff_material(config);
}

}  // namespace

bool parse_solver_config(const YAML::Node& solver, SolverConfig& config, std::string& error) {
  if (!solver) {
    error = "solver: missing section";
    return false;
  }
  try {
    parse(solver, config);
    return true;
  } catch (const ConfigError& e) {
    error = e.what();
  } catch (const YAML::Exception& e) {
    error = std::string("solver: ") + e.what();
  }
  return false;
}

bool parse_run_config(const YAML::Node& root, SolverConfig& config, std::string& tetray_yaml,
                      std::string& error) {
  try {
    if (!root.IsMap()) fail(root, "(document)", "expected a map with solver and tetray sections");
    for (const auto& entry : root) {
      const std::string name = key_name(entry.first, "(document)");
      if (name != "solver" && name != "tetray")
        fail(entry.first, name, "unknown key; expected solver and tetray");
    }
    if (!root["tetray"]) {
      error = "tetray: missing section";
      return false;
    }
    if (!parse_solver_config(root["solver"], config, error)) return false;
    YAML::Emitter emitter;
    emitter << root["tetray"];
    tetray_yaml = emitter.c_str();
    return true;
  } catch (const ConfigError& e) {
    error = e.what();
  } catch (const YAML::Exception& e) {
    error = std::string("(document): ") + e.what();
  }
  return false;
}

}  // namespace minisolver
