#include "support/reference_camera.hpp"

#include <cmath>
#include <numbers>

namespace tetray::test {
namespace {

// Spelled out here rather than taken from render/core/vec.hpp, so that the reference's rays do
// not depend on the renderer's vector operations either.
Vec3d difference(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

Vec3d cross_product(Vec3d a, Vec3d b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

double dot_product(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vec3d unit(Vec3d a) {
  const double norm = std::sqrt(dot_product(a, a));
  return {a.x / norm, a.y / norm, a.z / norm};
}

}  // namespace

ReferenceCamera::ReferenceCamera(const render::Camera& camera)
    : eye_(camera.eye),
      forward_(unit(difference(camera.look_at, camera.eye))),
      right_(unit(cross_product(forward_, camera.up))),
      up_(cross_product(right_, forward_)),
      tan_half_fov_(std::tan(camera.fov_deg / 2 * std::numbers::pi / 180)),
      width_(camera.width),
      height_(camera.height) {}

Vec3d ReferenceCamera::pixel_direction(int i, int j) const {
  const double aspect = static_cast<double>(width_) / height_;
  const double ndc_x = (2 * (i + 0.5) / width_ - 1) * tan_half_fov_ * aspect;
  const double ndc_y = (1 - 2 * (j + 0.5) / height_) * tan_half_fov_;
  return unit({forward_.x + ndc_x * right_.x + ndc_y * up_.x,
               forward_.y + ndc_x * right_.y + ndc_y * up_.y,
               forward_.z + ndc_x * right_.z + ndc_y * up_.z});
}

double ReferenceCamera::depth(Vec3d point) const {
  return dot_product(difference(point, eye_), forward_);
}

}  // namespace tetray::test
