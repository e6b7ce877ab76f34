#include "support/reference_tet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetray::test {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A tet whose |6 volume| is below this times (longest edge)^3 has no volume: its field is not
// defined inside, and the reference uses the limit of thinner and thinner slivers instead
// (the isopolygon lying flat in the tet's plane), which keeps a mesh with it watertight.
constexpr double kFlatVolume = 1e-10;
// A crossing this far (as a fraction of the in-tet stretch) outside the stretch still counts:
// it lies on a tet face, where double rounding of the barycentric coordinates decides.
constexpr double kOnFaceSlack = 1e-9;

// Vertices of the face opposite vertex k.
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// Distance between the segments [p1, q1] and [p2, q2] (Ericson, Real-Time Collision
// Detection §5.1.9), exact zero tests so that zero-length segments are points.
double segment_distance(Vec3d p1, Vec3d q1, Vec3d p2, Vec3d q2) {
  const Vec3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a == 0 && e != 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else if (a != 0) {
    const double c = dot(d1, r);
    if (e == 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), denom = a * e - b * b;
      s = denom != 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return length((p1 + s * d1) - (p2 + t * d2));
}

double ray_segment_distance(const Ray& ray, double t_max, Vec3d a, Vec3d b) {
  return segment_distance(ray.origin, ray.origin + t_max * ray.direction, a, b);
}

}  // namespace

ReferenceTet::ReferenceTet(const std::array<Vec3d, 4>& points, const std::array<double, 4>& values,
                           std::uint32_t id)
    : p_(points), f_(values), id_(id) {
  center_ = 0.25 * (p_[0] + p_[1] + p_[2] + p_[3]);
  double longest = 0;
  for (const auto& e : kEdges) longest = std::max(longest, length(p_[e[1]] - p_[e[0]]));
  for (const Vec3d& p : p_) radius_ = std::max(radius_, length(p - center_));

  const double volume6 = dot(p_[1] - p_[0], cross(p_[2] - p_[0], p_[3] - p_[0]));
  flat_ = !(std::abs(volume6) > kFlatVolume * longest * longest * longest);
  if (flat_) {
    // The plane through the largest face; a tet with no such face (a segment or a point)
    // keeps a zero normal and is never hit.
    for (const auto& face : kFace) {
      const Vec3d n = cross(p_[face[1]] - p_[face[0]], p_[face[2]] - p_[face[0]]);
      if (length(n) > length(normal_)) normal_ = n;
    }
    if (!(length(normal_) > 1e-12 * longest * longest)) normal_ = {};
    return;
  }
  for (int k = 0; k < 4; ++k) {
    const Vec3d& a = p_[kFace[k][0]];
    const Vec3d n = cross(p_[kFace[k][1]] - a, p_[kFace[k][2]] - a);
    lambda_gradient_[k] = (1.0 / dot(n, p_[k] - a)) * n;
    lambda_offset_[k] = -dot(lambda_gradient_[k], a);
    normal_ = normal_ + f_[k] * lambda_gradient_[k];
  }
}

double ReferenceTet::min_value() const {
  return std::min(std::min(f_[0], f_[1]), std::min(f_[2], f_[3]));
}

std::optional<double> ReferenceTet::reach(const Ray& ray, double pad) const {
  const Vec3d v = center_ - ray.origin;
  const double along = dot(v, ray.direction);
  const double distance2 = along < 0 ? dot(v, v) : dot(v, v) - along * along;
  const double sphere = radius_ + pad;
  if (distance2 > sphere * sphere) return std::nullopt;
  return along - sphere;
}

std::optional<FieldOnRay> ReferenceTet::field_on_ray(const Ray& ray) const {
  if (flat_) return std::nullopt;
  // lambda_k(t) = a_k + b_k t; the tet is where all four are >= 0.
  std::array<double, 4> a{}, b{};
  double t_in = 0, t_out = kInfinity;
  for (int k = 0; k < 4; ++k) {
    a[k] = dot(lambda_gradient_[k], ray.origin) + lambda_offset_[k];
    b[k] = dot(lambda_gradient_[k], ray.direction);
    if (b[k] > 0) {
      t_in = std::max(t_in, -a[k] / b[k]);
    } else if (b[k] < 0) {
      t_out = std::min(t_out, -a[k] / b[k]);
    } else if (a[k] < 0) {
      return std::nullopt;
    }
  }
  if (!(t_in <= t_out)) return std::nullopt;
  const auto field_at = [&](double t) {
    double f = 0;
    for (int k = 0; k < 4; ++k) f += (a[k] + b[k] * t) * f_[k];
    return f;
  };
  return FieldOnRay{t_in, t_out, field_at(t_in), field_at(t_out)};
}

std::optional<double> ReferenceTet::intersect(const Ray& ray, double iso) const {
  const Isopolygon polygon = isopolygon(iso);
  if (polygon.size == 0) return std::nullopt;
  if (flat_) return intersect_flat(ray, polygon);
  const std::optional<FieldOnRay> segment = field_on_ray(ray);
  if (!segment) return std::nullopt;
  const double df = segment->f_out - segment->f_in;
  if (df == 0) {
    // The stretch lies in the level plane (only exactly on it); its near end is the hit.
    return segment->f_in == iso ? std::optional(segment->t_in) : std::nullopt;
  }
  const double s = (iso - segment->f_in) / df;
  if (s < -kOnFaceSlack || s > 1 + kOnFaceSlack) return std::nullopt;
  return segment->t_in + std::clamp(s, 0.0, 1.0) * (segment->t_out - segment->t_in);
}

std::optional<double> ReferenceTet::intersect_flat(const Ray& ray,
                                                   const Isopolygon& polygon) const {
  const double facing = dot(normal_, ray.direction);
  if (facing == 0) return std::nullopt;
  const double t = dot(normal_, p_[0] - ray.origin) / facing;
  if (t < 0) return std::nullopt;
  const Vec3d x = ray.origin + t * ray.direction;
  // Inside a convex polygon: on the same side of every edge.
  bool any_positive = false, any_negative = false;
  for (int i = 0; i < polygon.size; ++i) {
    const Vec3d& a = polygon.corners[i];
    const Vec3d& b = polygon.corners[(i + 1) % polygon.size];
    const double side = dot(cross(b - a, x - a), normal_);
    any_positive = any_positive || side > 0;
    any_negative = any_negative || side < 0;
  }
  if (any_positive && any_negative) return std::nullopt;
  return t;
}

double ReferenceTet::abs_cos(const Ray& ray) const {
  return std::abs(dot(normal_, ray.direction)) / length(normal_);
}

Isopolygon ReferenceTet::isopolygon(double iso) const {
  std::array<int, 4> above{}, below{};
  int above_count = 0, below_count = 0;
  for (int k = 0; k < 4; ++k) {
    if (f_[k] >= iso) {
      above[above_count++] = k;
    } else {
      below[below_count++] = k;
    }
  }
  Isopolygon polygon;
  if (above_count == 0 || below_count == 0) return polygon;
  // The level set crosses every edge from an above to a below vertex.
  const auto crossing = [&](int up, int down) {
    const double w = (iso - f_[down]) / (f_[up] - f_[down]);
    return p_[down] + w * (p_[up] - p_[down]);
  };
  if (above_count == 2) {
    // Consecutive corners share a tet vertex, hence a tet face: this order walks the quad.
    polygon.corners = {crossing(above[0], below[0]), crossing(above[0], below[1]),
                       crossing(above[1], below[1]), crossing(above[1], below[0])};
    polygon.size = 4;
    return polygon;
  }
  for (int i = 0; i < 3; ++i) {
    polygon.corners[i] =
        above_count == 1 ? crossing(above[0], below[i]) : crossing(above[i], below[0]);
  }
  polygon.size = 3;
  return polygon;
}

double ReferenceTet::isopolygon_edge_distance(const Ray& ray, double t_max, double iso) const {
  const Isopolygon polygon = isopolygon(iso);
  double nearest = kInfinity;
  for (int i = 0; i < polygon.size; ++i) {
    nearest = std::min(nearest, ray_segment_distance(ray, t_max, polygon.corners[i],
                                                     polygon.corners[(i + 1) % polygon.size]));
  }
  return nearest;
}

double ReferenceTet::tet_edge_distance(const Ray& ray, double t_max) const {
  double nearest = kInfinity;
  for (const auto& e : kEdges) {
    nearest = std::min(nearest, ray_segment_distance(ray, t_max, p_[e[0]], p_[e[1]]));
  }
  return nearest;
}

}  // namespace tetray::test
