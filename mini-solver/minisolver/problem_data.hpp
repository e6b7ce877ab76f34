// What a problem prescribes, as functions of position and time: the initial state everywhere and
// the Dirichlet values on fixed faces come from the same `prescribed` function.
#pragma once

#include <functional>
#include <string>

#include "minisolver/mesh.hpp"

namespace minisolver {

struct HeatData {
  std::function<double(const Vec3&, double)> prescribed;  // temperature
  std::function<double(const Vec3&, double)> source;      // heat per unit volume and time
};

struct Kinematics {
  Vec3 displacement{};
  Vec3 velocity{};
  Vec3 acceleration{};
};

struct ElasticData {
  std::function<Kinematics(const Vec3&, double)> prescribed;
  std::function<Vec3(const Vec3&, double)> body_force;  // per unit volume
};

// The result of one time step; on failure the state is that of the last good step.
struct StepOutcome {
  bool ok = true;
  std::string message;
  int iterations = 0;
};

}  // namespace minisolver
