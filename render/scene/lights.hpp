// The lights of a scene (Wald et al. 2007, §7): a headlight (at the eye), point lights and
// directional lights, each of which may cast shadows. The diffuse part of the shading is the mean
// of the lights' Lambert terms, so more lights never brighten past the surface color.
// Two-sided: the surface's normal is turned towards the viewer; the headlight gives |cos|, a
// point or directional light max(0, cos) on that side.
#pragma once

#include "render/core/vec.hpp"

namespace tetray::render {

enum class LightKind { headlight, point, directional };

struct Light {
  LightKind kind = LightKind::headlight;
  Vec3d vector{};        // point: the position (world); directional: the direction light travels
  bool shadows = false;  // point and directional lights only
};

inline constexpr int kMaxLights = 8;

struct Lights {
  int count = 0;  // 0: a headlight alone
  Light light[kMaxLights];

  // Only the one headlight of docs/architecture.md §3 (the shading of a scene without lights).
  bool headlight_only() const {
    return count == 0 || (count == 1 && light[0].kind == LightKind::headlight);
  }
  int shadow_count() const {
    int n = 0;
    for (int k = 0; k < count; ++k) n += light[k].shadows;
    return n;
  }
};

}  // namespace tetray::render
