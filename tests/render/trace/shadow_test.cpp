// Shadows (Wald et al. 2007, §7): the occlusion bits of tetray's shadow rays against the
// double-precision reference's segments from the same hit points (taken from the image's depth,
// as every rank takes them), with and without a clip region; the shading of several lights
// against its formula on a plane; and shadows removing exactly the shadowing light's term.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "render/trace/shadow_rays.hpp"
#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

const int kSide = scaled_side(64);

render::TraceOptions shadowing_lights() {
  render::TraceOptions options;
  options.lights.count = 3;
  options.lights.light[0] = {render::LightKind::headlight, {}, false};
  options.lights.light[1] = {render::LightKind::point, {1.6, 2.4, 0.9}, true};
  options.lights.light[2] = {render::LightKind::directional, {-0.3, -1.0, -0.6}, true};
  return options;
}

double max_abs(Vec3d v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// The gap tetray leaves at the surface end of a shadow ray (shadow_rays.cpp), in double.
double surface_gap(Vec3d point, Vec3d eye, double distance) {
  return 1e-4 * std::max({distance, max_abs(point), max_abs(eye)});
}

struct ShadowCounts {
  std::size_t rays = 0, blocked = 0, exempt = 0, mismatches = 0;
};

void expect_shadow_agreement(const render::TraceOptions& options, const std::string& label) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const double isovalues[] = {0.0, 0.5};
  const auto surfaces = make_surfaces(isovalues);
  const ReferenceIntersector reference(scene.volume, isovalues_of(surfaces), options.clip);
  const double scale = reference.length_scale();
  ShadowCounts total;
  int index = 0;
  for (const render::Camera& camera : standard_cameras(kSide, kSide)) {
    if (index++ == 5) break;  // the far camera's hit points carry its rounding
    const render::Framebuffer image =
        render::trace(scene.volume, scene.bvh, camera, surfaces, options);
    const auto occluded =
        render::trace_shadow_rays(scene.volume, scene.bvh, camera, surfaces, options, image.depth);
    const ReferenceCamera rays(camera);
    ShadowCounts counts;
    for (int j = 0; j < camera.height; ++j)
      for (int i = 0; i < camera.width; ++i) {
        const std::size_t p = image.index(i, j);
        if (image.hit[p] == render::kNoHit) continue;
        const Vec3d d = rays.pixel_direction(i, j);
        const Vec3d point =
            camera.eye + (image.depth[p] / rays.depth(camera.eye + d)) * d - scene.volume.origin;
        int bit = 0;
        for (int k = 0; k < options.lights.count; ++k) {
          const render::Light& light = options.lights.light[k];
          if (!light.shadows) continue;
          Vec3d to_light = -1.0 * light.vector;
          double t_max = 4 * scale;
          if (light.kind == render::LightKind::point) {
            to_light = light.vector - scene.volume.origin - point;
            t_max = length(to_light);
          }
          to_light = normalize(to_light);
          const double gap = surface_gap(point, camera.eye - scene.volume.origin,
                                         light.kind == render::LightKind::point ? t_max : 0);
          const ReferenceShadow ref = reference.shadow_ray(point, to_light, gap, t_max);
          const bool got = (occluded[p] >> bit++) & 1;
          ++counts.rays;
          counts.blocked += ref.blocked;
          if (ref.isopolygon_edge_distance < 1e-5 || ref.clip_boundary_distance < 1e-5 ||
              ref.nearest_t < 2 * gap) {
            ++counts.exempt;
            continue;
          }
          if (got != ref.blocked) {
            ++counts.mismatches;
            if (counts.mismatches <= 5)
              ADD_FAILURE() << label << " camera " << index - 1 << " pixel " << i << "," << j
                            << " light " << k << ": tetray " << got << " reference " << ref.blocked
                            << " at t " << ref.nearest_t;
          }
        }
      }
    std::cout << "[ shadows ] " << label << " camera " << index - 1 << ": rays " << counts.rays
              << ", blocked " << counts.blocked << ", exempt " << counts.exempt << ", mismatches "
              << counts.mismatches << "\n";
    total.rays += counts.rays;
    total.blocked += counts.blocked;
    total.exempt += counts.exempt;
    total.mismatches += counts.mismatches;
  }
  // Cameras inside the mesh see only shadowed hit points; those outside see both.
  EXPECT_EQ(total.mismatches, 0u) << label;
  EXPECT_GT(total.blocked, total.rays / 10) << label << ": the scene must cast shadows";
  EXPECT_LT(total.blocked, total.rays * 9 / 10) << label << ": and light some of it";
  EXPECT_LT(total.exempt, total.rays / 40) << label;
}

TEST(Shadows, AgreeWithTheReference) { expect_shadow_agreement(shadowing_lights(), "lights"); }

TEST(Shadows, AgreeWithTheReferenceInsideAClipRegion) {
  render::TraceOptions options = shadowing_lights();
  options.clip.has_box = true;
  options.clip.box_lo = {-1.2, -1.2, -1.2};
  options.clip.box_hi = {0.2, 1.2, 1.2};
  options.clip.planes[0] = {{0, 0.4, 0}, {0, 1, 0.2}};
  options.clip.plane_count = 1;
  expect_shadow_agreement(options, "lights and clip");
}

// The plane z = 0.25 seen from above, lit by the headlight and a point light: the pixel's light
// is ambient + (1 - ambient) (|cos| to the eye + max(0, cos) to the light) / 2.
TEST(Lights, ShadeByTheMeanOfTheLambertTerms) {
  const BoxMesh box = jittered_box(4, 0.0);
  const auto f = sample_field(box.points, [](Vec3d p) { return p.z; });
  RenderScene scene = load_scene(box.points, box.tets, f);
  const render::Camera camera = look_at({0.2, 0.1, 3}, {0, 0, 0}, 30, 32, 32);
  render::TraceOptions options;
  options.lights.count = 2;
  options.lights.light[0] = {render::LightKind::headlight, {}, false};
  const Vec3d light{0.6, -0.4, 1.5};
  options.lights.light[1] = {render::LightKind::point, light, true};
  const render::IsoSurface surfaces[] = {{0.25f, {1, 1, 1}}};
  std::vector<render::Framebuffer> terms;
  render::Framebuffer image;
  render::trace_into(image, scene.volume, scene.bvh, camera, surfaces, options, nullptr, &terms);
  ASSERT_EQ(terms.size(), 1u);
  const ReferenceCamera rays(camera);
  std::size_t checked = 0;
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = image.index(i, j);
      if (image.hit[p] == render::kNoHit) continue;
      const Vec3d d = rays.pixel_direction(i, j);
      const Vec3d hit = camera.eye + ((0.25 - camera.eye.z) / d.z) * d;
      const double to_light = std::max(0.0, normalize(light - hit).z);
      const double ambient = options.ambient;
      EXPECT_NEAR(image.rgba[4 * p], ambient + (1 - ambient) * (std::abs(d.z) + to_light) / 2,
                  1e-4);
      EXPECT_NEAR(terms[0].rgba[4 * p], (1 - ambient) * to_light / 2, 1e-4);
      ++checked;
    }
  EXPECT_GT(checked, 500u);
  // Occluded everywhere: only the headlight's part stays.
  std::vector<std::uint8_t> all(image.pixel_count(), 1);
  render::apply_shadows(image, terms, all);
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = image.index(i, j);
      if (image.hit[p] == render::kNoHit) continue;
      const Vec3d d = rays.pixel_direction(i, j);
      EXPECT_NEAR(image.rgba[4 * p], options.ambient + (1 - options.ambient) * std::abs(d.z) / 2,
                  1e-4);
    }
}

// The planes x + z = 0.6 and x + z = -0.6 of the box [-1, 1]^3 seen from above, listed in
// descending order with colors of their own: each pixel takes the color of the surface it hit
// (the upper one where it lies in the box, else the lower one) times the headlight's
// ambient + (1 - ambient) |cos|, with alpha 1, and the background stays zero.
TEST(Lights, EachHitTakesTheColorOfItsSurface) {
  const BoxMesh box = jittered_box(4, 0.0);
  const auto f = sample_field(box.points, [](Vec3d p) { return p.x + p.z; });
  RenderScene scene = load_scene(box.points, box.tets, f);
  const render::Camera camera = look_at({0.1, 0.05, 4}, {0, 0, 0}, 40, 48, 48);
  const render::IsoSurface surfaces[] = {{0.6f, {0.9f, 0.2f, 0.1f}}, {-0.6f, {0.1f, 0.5f, 0.8f}}};
  const render::TraceOptions options;
  const render::Framebuffer image =
      render::trace(scene.volume, scene.bvh, camera, surfaces, options);
  const ReferenceCamera rays(camera);
  std::size_t hits_per_surface[2] = {0, 0};
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const std::size_t p = image.index(i, j);
      const float* rgba = &image.rgba[4 * p];
      const Vec3d d = rays.pixel_direction(i, j);
      // The first of the planes whose crossing lies in the box, well inside its sides.
      int hit_surface = -1;
      for (int s = 0; s < 2 && hit_surface < 0; ++s) {
        const Vec3d at =
            camera.eye + ((surfaces[s].value - camera.eye.x - camera.eye.z) / (d.x + d.z)) * d;
        if (max_abs(at) < 0.98) hit_surface = s;
        if (max_abs(at) < 1.02 && max_abs(at) >= 0.98) hit_surface = 2;  // too near a side
      }
      if (hit_surface == 2) continue;
      if (hit_surface < 0) {
        EXPECT_EQ(image.hit[p], render::kNoHit);
        for (int k = 0; k < 4; ++k) EXPECT_EQ(rgba[k], 0.0f);
        continue;
      }
      ASSERT_NE(image.hit[p], render::kNoHit) << i << ", " << j;
      const double light =
          options.ambient + (1 - options.ambient) * std::abs(d.x + d.z) / std::sqrt(2.0);
      const render::Rgb& color = surfaces[hit_surface].color;
      EXPECT_NEAR(rgba[0], color.r * light, 1e-5);
      EXPECT_NEAR(rgba[1], color.g * light, 1e-5);
      EXPECT_NEAR(rgba[2], color.b * light, 1e-5);
      EXPECT_EQ(rgba[3], 1.0f);
      ++hits_per_surface[hit_surface];
    }
  EXPECT_GT(hits_per_surface[0], 400u);
  EXPECT_GT(hits_per_surface[1], 200u);
}

// Shadow rays only from the hit points a shadowing light reaches (shadow_ray_depths): a light
// behind part of the surface leaves those points black in its term, and the shadowed image is
// the one of rays from every hit point, bit for bit, with fewer rays.
TEST(Shadows, RaysOnlyWhereALightReachesGiveTheSameImage) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0, 0.5});
  const render::TraceOptions options = shadowing_lights();
  int index = 0;
  std::size_t hits = 0, left_out = 0;
  for (const render::Camera& camera : standard_cameras(kSide, kSide)) {
    render::Framebuffer image;
    std::vector<render::Framebuffer> terms;
    render::trace_into(image, scene.volume, scene.bvh, camera, surfaces, options, nullptr, &terms);
    ASSERT_EQ(terms.size(), 2u);
    const std::vector<float> reached = render::shadow_ray_depths(image, terms);
    render::Framebuffer every = image, some = image;
    render::apply_shadows(
        every, terms,
        render::trace_shadow_rays(scene.volume, scene.bvh, camera, surfaces, options, image.depth));
    render::apply_shadows(
        some, terms,
        render::trace_shadow_rays(scene.volume, scene.bvh, camera, surfaces, options, reached));
    EXPECT_EQ(image_difference(some, every), "") << "camera " << index++;
    for (std::size_t p = 0; p < image.pixel_count(); ++p) {
      if (image.hit[p] == render::kNoHit) continue;
      ++hits;
      const bool black = std::all_of(terms.begin(), terms.end(), [&](const auto& t) {
        return t.rgba[4 * p] == 0 && t.rgba[4 * p + 1] == 0 && t.rgba[4 * p + 2] == 0;
      });
      EXPECT_EQ(reached[p] == image.depth[p], !black);
      left_out += black;
    }
  }
  // Seen from the cameras around the gyroid, many points face away from both lights (about half
  // here), and many do not.
  EXPECT_GT(left_out, hits / 10);
  EXPECT_LT(left_out, hits - hits / 10);
}

// A headlight alone, listed or not, shades as docs/architecture.md §3 says, bit for bit.
TEST(Lights, AListedHeadlightIsTheDefaultShading) {
  const GyroidTwist data = gyroid(5);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0});
  render::TraceOptions listed;
  listed.lights.count = 1;
  const render::Camera camera = benchmark_camera(32);
  EXPECT_EQ(image_difference(render::trace(scene.volume, scene.bvh, camera, surfaces, {}),
                             render::trace(scene.volume, scene.bvh, camera, surfaces, listed)),
            "");
}

// The adaptor hands each image to its writer thread by moving it and traces the next step into
// the moved-from image, whose sizes remain while its storage is gone.
TEST(TraceInto, AMovedFromImageGetsNewStorage) {
  const GyroidTwist data = gyroid(5);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0});
  const render::Camera camera = benchmark_camera(40);
  render::Framebuffer image = render::trace(scene.volume, scene.bvh, camera, surfaces, {});
  const render::Framebuffer first = image;
  const render::Framebuffer moved = std::move(image);
  render::trace_into(image, scene.volume, scene.bvh, camera, surfaces, {});
  EXPECT_EQ(image_difference(image, first), "");
}

// The image and the shadowing lights' terms are kept from frame to frame (trace_into reuses
// their storage where the size fits): every frame writes each of their pixels, so a frame traced
// into the last one's image and terms is the frame traced into fresh ones, bit for bit, whatever
// the last one held (another camera, a clip box that left some pixels to the background).
TEST(Shadows, TermsKeptFromTheFrameBeforeGiveTheFreshFrame) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  const auto surfaces = make_surfaces(std::vector<double>{0.0, 0.5});
  render::TraceOptions with_box = shadowing_lights();
  with_box.clip.has_box = true;
  with_box.clip.box_lo = {-1.2, -1.2, -1.2};
  with_box.clip.box_hi = {0.2, 1.2, 1.2};
  const render::TraceOptions& clipped = with_box;
  const render::TraceOptions plain = shadowing_lights();
  render::Framebuffer kept_image;
  std::vector<render::Framebuffer> kept_terms;
  int frame = 0;
  // Near (the volume fills the image), then far (background all around): the far frame's
  // background lands on what the near one hit.
  const render::Camera cameras[] = {look_at({0.4, 0.3, 1.6}, {0, 0, 0}, 60, kSide, kSide),
                                    look_at({20, 15, 55}, {0, 0, 0}, 10, kSide, kSide)};
  for (const render::TraceOptions* options : {&plain, &clipped}) {
    for (const render::Camera& camera : cameras) {
      render::trace_into(kept_image, scene.volume, scene.bvh, camera, surfaces, *options, nullptr,
                         &kept_terms);
      render::Framebuffer image;
      std::vector<render::Framebuffer> terms;
      render::trace_into(image, scene.volume, scene.bvh, camera, surfaces, *options, nullptr,
                         &terms);
      EXPECT_EQ(image_difference(kept_image, image), "") << "frame " << frame;
      ASSERT_EQ(kept_terms.size(), terms.size());
      for (std::size_t j = 0; j < terms.size(); ++j)
        EXPECT_EQ(image_difference(kept_terms[j], terms[j]), "")
            << "frame " << frame << " light " << j;
      ++frame;
    }
  }
  EXPECT_GE(frame, 4);
}

}  // namespace
}  // namespace tetray::test
