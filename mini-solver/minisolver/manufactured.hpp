// Manufactured solutions: a chosen exact field, and the source or body force that makes it solve
// the equations, so the discretization error is known exactly. Fields are separable,
// shape(x) * profile(t), on the unit cube [0,1]^3.
#pragma once

#include <array>

#include "minisolver/assembly.hpp"
#include "minisolver/problem_data.hpp"

namespace minisolver {

using Mat3 = std::array<Vec3, 3>;

// The spatial factor: sin(pi x) sin(pi y) sin(pi z), zero on the cube's faces, or the linear
// 1 + x + 2y - z, which P1 elements represent exactly (only time errors remain).
enum class Shape { sine, linear };
// The temporal factor: 1 + t (linear; the time schemes integrate it exactly) or
// 1 + sin(pi t + 0.5) (every derivative nonzero).
enum class Profile { linear, oscillating };

struct Separable {
  Shape shape;
  Profile profile;

  double value(const Vec3& x) const;
  Vec3 gradient(const Vec3& x) const;
  Mat3 hessian(const Vec3& x) const;
  // d^k/dt^k of the profile, k = 0, 1, 2.
  double profile_derivative(double t, int k) const;
};

// Temperature u = S(x) w(t) for unit conductivity and capacity: source = S w' - w laplacian(S).
HeatData manufactured_heat(const Separable& field);

// Displacement u = S(x) w(t) direction.
ElasticData manufactured_elastic(const Separable& field, const Vec3& direction, const Lame& lame,
                                 double density);

// Divergence-free displacement u = (dS/dy, -dS/dx, 0) w(t) with S the sine shape: its body force
// does not depend on lambda, so any growth of the error as lambda grows is volumetric locking.
ElasticData manufactured_solenoidal(Profile profile, const Lame& lame, double density);

}  // namespace minisolver
