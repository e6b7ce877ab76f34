// One tet of the reference intersector, in double precision. This re-derives the isosurface
// of a linear tet from first principles (barycentric coordinates from the face planes) and
// shares no code with the renderer's isopolygon kernels, so the two can check each other.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "render/core/vec.hpp"

namespace tetray::test {

using render::Vec3d;

struct Ray {
  Vec3d origin;
  Vec3d direction;  // unit length
};

// The stretch of a ray inside a tet (clipped to t >= 0) and the linear field at its ends.
struct FieldOnRay {
  double t_in = 0, t_out = 0;
  double f_in = 0, f_out = 0;
};

// The isopolygon of one isovalue: the level set f = iso inside the tet, with its corners in
// cyclic order. Empty unless some vertex counts as above (f >= iso) and some as below.
struct Isopolygon {
  std::array<Vec3d, 4> corners{};
  int size = 0;
};

class ReferenceTet {
 public:
  ReferenceTet(const std::array<Vec3d, 4>& points, const std::array<double, 4>& values,
               std::uint32_t id);

  std::uint32_t id() const { return id_; }
  double min_value() const;
  bool is_flat() const { return flat_; }

  // When the ray passes within `pad` of the tet's bounding sphere (a cheap pre-test): a lower
  // bound of the ray parameter of any point of the tet (within `pad`).
  std::optional<double> reach(const Ray& ray, double pad) const;

  // The ray's parameter interval inside the tet from the four face planes; empty when the ray
  // misses it or the tet has no volume.
  std::optional<FieldOnRay> field_on_ray(const Ray& ray) const;

  // Nearest t >= 0 where the ray meets the isopolygon of `iso`.
  std::optional<double> intersect(const Ray& ray, double iso) const;

  // |cos| of the angle between the ray and the isopolygon's normal (Lambert headlight).
  double abs_cos(const Ray& ray) const;

  Isopolygon isopolygon(double iso) const;

  // Smallest distance from the ray's stretch [0, t_max] to an edge of the isopolygon of
  // `iso` (infinity when there is none), and to an edge of the tet.
  double isopolygon_edge_distance(const Ray& ray, double t_max, double iso) const;
  double tet_edge_distance(const Ray& ray, double t_max) const;

 private:
  std::optional<double> intersect_flat(const Ray& ray, const Isopolygon& polygon) const;

  std::array<Vec3d, 4> p_;
  std::array<double, 4> f_;
  std::uint32_t id_;
  Vec3d center_{};
  double radius_ = 0;
  // Non-flat tets: barycentric coordinate k is dot(lambda_gradient_[k], x) + lambda_offset_[k].
  std::array<Vec3d, 4> lambda_gradient_{};
  std::array<double, 4> lambda_offset_{};
  // Field gradient, or for a flat tet the normal of its plane (zero when it has no plane).
  Vec3d normal_{};
  bool flat_ = false;
};

}  // namespace tetray::test
