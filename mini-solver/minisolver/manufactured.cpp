#include "minisolver/manufactured.hpp"

#include <cmath>
#include <numbers>

namespace minisolver {
namespace {

constexpr double pi = std::numbers::pi;

double trace(const Mat3& h) { return h[0][0] + h[1][1] + h[2][2]; }

}  // namespace

double Separable::value(const Vec3& x) const {
  if (shape == Shape::linear) return 1 + x[0] + 2 * x[1] - x[2];
  return std::sin(pi * x[0]) * std::sin(pi * x[1]) * std::sin(pi * x[2]);
}

Vec3 Separable::gradient(const Vec3& x) const {
  if (shape == Shape::linear) return {1, 2, -1};
  const Vec3 s{std::sin(pi * x[0]), std::sin(pi * x[1]), std::sin(pi * x[2])};
  const Vec3 c{std::cos(pi * x[0]), std::cos(pi * x[1]), std::cos(pi * x[2])};
  return {pi * c[0] * s[1] * s[2], pi * s[0] * c[1] * s[2], pi * s[0] * s[1] * c[2]};
}

Mat3 Separable::hessian(const Vec3& x) const {
  Mat3 h{};
  if (shape == Shape::linear) return h;
  const Vec3 s{std::sin(pi * x[0]), std::sin(pi * x[1]), std::sin(pi * x[2])};
  const Vec3 c{std::cos(pi * x[0]), std::cos(pi * x[1]), std::cos(pi * x[2])};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int k = 3 - i - j;  // the third axis when i != j
      h[i][j] = i == j ? -pi * pi * s[0] * s[1] * s[2] : pi * pi * c[i] * c[j] * s[k];
    }
  return h;
}

double Separable::profile_derivative(double t, int k) const {
  if (profile == Profile::linear) return k == 0 ? 1 + t : (k == 1 ? 1 : 0);
  const double phase = pi * t + 0.5;
  if (k == 0) return 1 + std::sin(phase);
  if (k == 1) return pi * std::cos(phase);
  return -pi * pi * std::sin(phase);
}

HeatData manufactured_heat(const Separable& field) {
  return {
      [field](const Vec3& x, double t) { return field.value(x) * field.profile_derivative(t, 0); },
      [field](const Vec3& x, double t) {
        return field.value(x) * field.profile_derivative(t, 1) -
               field.profile_derivative(t, 0) * trace(field.hessian(x));
      }};
}

ElasticData manufactured_elastic(const Separable& field, const Vec3& direction, const Lame& lame,
                                 double density) {
  auto prescribed = [field, direction](const Vec3& x, double t) {
    Kinematics k;
    const double s = field.value(x);
    for (int i = 0; i < 3; ++i) {
      k.displacement[i] = s * field.profile_derivative(t, 0) * direction[i];
      k.velocity[i] = s * field.profile_derivative(t, 1) * direction[i];
      k.acceleration[i] = s * field.profile_derivative(t, 2) * direction[i];
    }
    return k;
  };
  // div sigma = (lambda + mu) H c + mu tr(H) c for u = S c.
  auto force = [field, direction, lame, density](const Vec3& x, double t) {
    const Mat3 h = field.hessian(x);
    const double w = field.profile_derivative(t, 0);
    Vec3 f{};
    for (int i = 0; i < 3; ++i) {
      const double hc = dot(h[i], direction);
      const double divergence_of_stress =
          (lame.lambda + lame.mu) * hc + lame.mu * trace(h) * direction[i];
      f[i] = density * field.value(x) * field.profile_derivative(t, 2) * direction[i] -
             w * divergence_of_stress;
    }
    return f;
  };
  return {prescribed, force};
}

ElasticData manufactured_solenoidal(Profile profile, const Lame& lame, double density) {
  const Separable field{Shape::sine, profile};
  auto shape = [field](const Vec3& x) {
    const Vec3 g = field.gradient(x);
    return Vec3{g[1], -g[0], 0};
  };
  auto prescribed = [field, shape](const Vec3& x, double t) {
    const Vec3 u = shape(x);
    Kinematics k;
    for (int i = 0; i < 3; ++i) {
      k.displacement[i] = u[i] * field.profile_derivative(t, 0);
      k.velocity[i] = u[i] * field.profile_derivative(t, 1);
      k.acceleration[i] = u[i] * field.profile_derivative(t, 2);
    }
    return k;
  };
  // Derivatives of the sine shape are eigenfunctions of the Laplacian too: lap u = -3 pi^2 u.
  auto force = [field, shape, lame, density](const Vec3& x, double t) {
    const Vec3 u = shape(x);
    const double factor = density * field.profile_derivative(t, 2) +
                          3 * pi * pi * lame.mu * field.profile_derivative(t, 0);
    return Vec3{factor * u[0], factor * u[1], factor * u[2]};
  };
  return {prescribed, force};
}

}  // namespace minisolver
