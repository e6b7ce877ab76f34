// Small fixed-size vectors for geometry. Kernels that run per ray use the SIMD vocabulary in
// simd.hpp instead; these serve set-up code (camera, isopolygons, bounds).
#pragma once

#include <algorithm>
#include <cmath>

namespace tetray::render {

template <typename T>
struct Vec3 {
  T x{}, y{}, z{};

  constexpr T operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  constexpr T& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }
  template <typename U>
  constexpr explicit operator Vec3<U>() const {
    return {static_cast<U>(x), static_cast<U>(y), static_cast<U>(z)};
  }
};

using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;

template <typename T>
constexpr Vec3<T> operator+(Vec3<T> a, Vec3<T> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename T>
constexpr Vec3<T> operator-(Vec3<T> a, Vec3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
constexpr Vec3<T> operator-(Vec3<T> a) {
  return {-a.x, -a.y, -a.z};
}
template <typename T>
constexpr Vec3<T> operator*(T s, Vec3<T> a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <typename T>
constexpr T dot(Vec3<T> a, Vec3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
T length(Vec3<T> a) {
  return std::sqrt(dot(a, a));
}
template <typename T>
Vec3<T> normalize(Vec3<T> a) {
  return (T(1) / length(a)) * a;
}
template <typename T>
constexpr Vec3<T> min(Vec3<T> a, Vec3<T> b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
constexpr Vec3<T> max(Vec3<T> a, Vec3<T> b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

}  // namespace tetray::render
