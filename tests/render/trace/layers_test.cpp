// Transparency by depth peeling (Wald et al. 2007, §8.5) against the double-precision reference:
// each pixel's layers are the reference's hits along its ray in order (within the clip region),
// up to and with the first opaque one and at most max_layers, at the same distances and on the
// same surfaces, except for rays within 1e-6 of an isopolygon edge, near a clip plane or through
// two hits closer than the depth tolerance (whose order is rounding). Every packet size peels
// the same layers bitwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "render/trace/layer_shading.hpp"
#include "render/trace/shadow_rays.hpp"
#include "support/reference_comparison.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::test {
namespace {

const int kSide = scaled_side(48);

struct LayerCounts {
  std::size_t compared = 0, exempt = 0, layers = 0, peeled_beyond_first = 0;
  std::size_t count_mismatches = 0, depth_mismatches = 0, surface_mismatches = 0;
};

// The surface a fragment lies on, told by its alpha (every surface has its own opacity).
int surface_of(const render::Fragment& f, std::span<const render::IsoSurface> surfaces) {
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    if (f.rgba[3] == surfaces[s].opacity) return static_cast<int>(s);
  }
  return -1;
}

// The reference's layers a pixel must show: up to and with the first opaque one, at most max.
std::size_t expected_count(const ReferenceLayers& ref, std::span<const render::IsoSurface> surfaces,
                           int max_layers) {
  std::size_t count = 0;
  for (const ReferenceLayers::Layer& layer : ref.layers) {
    if (count == static_cast<std::size_t>(max_layers)) break;
    ++count;
    if (surfaces[static_cast<std::size_t>(layer.surface)].opacity >= 1) break;
  }
  return count;
}

LayerCounts compare_layers(const render::LayerImage& image, const ReferenceIntersector& reference,
                           const render::Camera& camera,
                           std::span<const render::IsoSurface> surfaces, int max_layers,
                           const std::string& label) {
  const ReferenceCamera rays(camera);
  LayerCounts counts;
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const ReferenceLayers ref = reference.trace_layers(rays, rays.pixel_direction(i, j));
      if (ref.isopolygon_edge_distance < kGrazingDistance ||
          ref.clip_boundary_distance < kClipBoundaryDistance ||
          ref.closest_layers < kDepthTolerance) {
        ++counts.exempt;
        continue;
      }
      ++counts.compared;
      const auto pixel = image.color.pixel(static_cast<std::size_t>(j) * camera.width + i);
      const std::size_t expected = expected_count(ref, surfaces, max_layers);
      counts.layers += pixel.size();
      counts.peeled_beyond_first += pixel.size() > 1;
      if (pixel.size() != expected) {
        if (++counts.count_mismatches <= 5)
          ADD_FAILURE() << label << " pixel (" << i << ", " << j << "): " << pixel.size()
                        << " layers, the reference " << expected;
        continue;
      }
      for (std::size_t l = 0; l < expected; ++l) {
        const double t = ref.layers[l].t;
        if (std::abs(pixel[l].depth_in - t) > kDepthTolerance * ref.length_scale &&
            ++counts.depth_mismatches <= 5)
          ADD_FAILURE() << label << " pixel (" << i << ", " << j << ") layer " << l << ": t "
                        << pixel[l].depth_in << ", the reference " << t;
        if (surface_of(pixel[l], surfaces) != ref.layers[l].surface &&
            ++counts.surface_mismatches <= 5)
          ADD_FAILURE() << label << " pixel (" << i << ", " << j << ") layer " << l << ": surface "
                        << surface_of(pixel[l], surfaces) << ", the reference "
                        << ref.layers[l].surface;
      }
    }
  return counts;
}

bool same_fragments(const render::FragmentImage& a, const render::FragmentImage& b) {
  if (a.begin != b.begin || a.fragments.size() != b.fragments.size()) return false;
  for (std::size_t k = 0; k < a.fragments.size(); ++k) {
    const render::Fragment &x = a.fragments[k], &y = b.fragments[k];
    if (x.depth_in != y.depth_in || x.depth_out != y.depth_out || x.key != y.key) return false;
    for (int c = 0; c < 4; ++c) {
      if (x.rgba[c] != y.rgba[c]) return false;
    }
  }
  return true;
}

void expect_layers_agree(std::span<const double> isovalues, std::span<const float> opacity,
                         int max_layers, const render::ClipRegion& clip, const std::string& label) {
  const GyroidTwist data = gyroid(8);
  const RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  for (std::size_t s = 0; s < surfaces.size(); ++s) surfaces[s].opacity = opacity[s];
  const ReferenceIntersector reference(scene.volume, isovalues_of(surfaces), clip);
  render::TraceOptions options;
  options.max_layers = max_layers;
  options.clip = clip;
  int index = 0;
  std::size_t compared = 0, peeled = 0;
  for (const render::Camera& camera : standard_cameras(kSide, kSide)) {
    const std::string name = label + " camera " + std::to_string(index++);
    render::LayerImage image;
    render::trace_layers(image, scene.volume, scene.bvh, camera, surfaces, options);
    const LayerCounts counts = compare_layers(image, reference, camera, surfaces, max_layers, name);
    std::cout << "[ layers ] " << name << ": " << counts.compared << " pixels compared ("
              << counts.exempt << " exempt), " << counts.layers << " layers, "
              << counts.peeled_beyond_first << " pixels with more than one\n";
    EXPECT_EQ(counts.count_mismatches + counts.depth_mismatches + counts.surface_mismatches, 0u)
        << name;
    compared += counts.compared;
    peeled += counts.peeled_beyond_first;
    EXPECT_LT(counts.exempt, counts.compared / 5) << name << ": too many pixels exempt";
    for (const render::PacketSize packet : render::kPacketSizes) {
      options.packet = packet;
      render::LayerImage again;
      render::trace_layers(again, scene.volume, scene.bvh, camera, surfaces, options);
      EXPECT_TRUE(same_fragments(image.color, again.color))
          << name << " packet " << render::to_string(packet);
    }
    options.packet = render::PacketSize::p32x32;
  }
  EXPECT_GT(peeled, compared / 10) << label << ": too few pixels with more than one layer";
}

// The gyroid with three surfaces at opacity 0.5.
struct HalfTransparentGyroid {
  GyroidTwist data = gyroid(8);
  RenderScene scene = load_scene(data.mesh.points, data.mesh.tets, data.field);
  std::vector<render::IsoSurface> surfaces = half_transparent({-0.5, 0.0, 0.5});

  static std::vector<render::IsoSurface> half_transparent(std::vector<double> isovalues) {
    std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
    for (render::IsoSurface& s : surfaces) s.opacity = 0.5f;
    return surfaces;
  }
};

TEST(Layers, TransparentSurfacesAgreeWithTheReference) {
  const double isovalues[] = {-0.5, 0.0, 0.5};
  const float opacity[] = {0.3f, 0.5f, 0.7f};
  expect_layers_agree(isovalues, opacity, render::kMaxLayers, {}, "transparent");
}

// Surfaces lying exactly in the mesh's faces: a ray meets the polygons of several tets at one
// distance, told apart only by their keys, and two surfaces at one isovalue. The tiles keep each
// ray's nearest layers from one test of their bins and the packets peel them layer by layer; they
// agree bitwise, ties included.
TEST(Layers, TiesInFacesTheTilesKeepAsThePacketsPeel) {
  const BoxMesh box = jittered_box(6, 0.0);
  const auto f = sample_field(box.points, [](Vec3d p) { return p.x; });
  const RenderScene scene = load_scene(box.points, box.tets, f);
  // Three of the grid's planes x = const, as the vertex store holds their values.
  std::vector<float> planes;
  for (const render::Vertex& v : scene.volume.vertices) planes.push_back(v.f);
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  ASSERT_EQ(planes.size(), 7u);
  // The last surface repeats the second's isovalue: its polygons meet every ray of the second's
  // at the same distance with the same key, one layer for the peeling.
  std::vector<render::IsoSurface> surfaces(4);
  const float opacity[] = {0.4f, 0.6f, 0.5f, 0.3f};
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    surfaces[s].value = planes[2 * (s % 3) + 1];
    surfaces[s].color = {0.2f + 0.3f * static_cast<float>(s), 0.5f, 0.8f};
    surfaces[s].opacity = opacity[s];
  }
  for (const int max_layers : {1, 2, 3, render::kMaxLayers}) {
    int index = 0;
    for (const render::Camera& camera : standard_cameras(kSide, kSide)) {
      render::TraceOptions options;
      options.max_layers = max_layers;
      render::LayerImage tiled, peeled;
      render::trace_layers(tiled, scene.volume, scene.bvh, camera, surfaces, options);
      options.packet = render::PacketSize::p16x16;
      render::trace_layers(peeled, scene.volume, scene.bvh, camera, surfaces, options);
      EXPECT_GT(peeled.color.fragments.size(), peeled.color.pixel_count() / 8);
      EXPECT_TRUE(same_fragments(tiled.color, peeled.color))
          << "max_layers " << max_layers << " camera " << index;
      ++index;
    }
  }
}

// Peeling stops at an opaque layer and at max_layers, and layers are clipped like first hits.
TEST(Layers, StopAtAnOpaqueLayerAndAtMaxLayersWithClipping) {
  const double isovalues[] = {-0.5, 0.0, 0.5};
  const float opacity[] = {0.3f, 1.0f, 0.7f};
  render::ClipRegion clip;
  clip.has_box = true;
  clip.box_lo = {-1.2, -1.2, -1.2};
  clip.box_hi = {0.05, 1.2, 1.2};
  expect_layers_agree(isovalues, opacity, 3, clip, "opaque and clipped");
}

// A layer's shadow rays only from the points a shadowing light reaches (keep_lit_layer_points):
// the shadowed layers are those of rays from every layer's points, bit for bit, with fewer rays.
TEST(Layers, ShadowRaysOnlyWhereALightReachesGiveTheSameLayers) {
  const HalfTransparentGyroid g;
  const RenderScene& scene = g.scene;
  const std::vector<render::IsoSurface>& surfaces = g.surfaces;
  render::TraceOptions options;
  options.lights.count = 3;
  options.lights.light[0] = {render::LightKind::headlight, {}, false};
  options.lights.light[1] = {render::LightKind::point, {1.6, 2.4, 0.9}, true};
  options.lights.light[2] = {render::LightKind::directional, {-0.3, -1.0, -0.6}, true};
  std::size_t every_points = 0, lit_points = 0;  // shadow rays traced per light
  const auto count = [](const std::vector<float>& depth) {
    return static_cast<std::size_t>(std::count_if(depth.begin(), depth.end(), [](float d) {
      return d < std::numeric_limits<float>::infinity();
    }));
  };
  int index = 0;
  for (const render::Camera& camera : standard_cameras(kSide, kSide)) {
    render::LayerImage every, lit;
    render::trace_layers(every, scene.volume, scene.bvh, camera, surfaces, options);
    render::trace_layers(lit, scene.volume, scene.bvh, camera, surfaces, options);
    std::vector<float> depth(every.color.pixel_count());
    for (int layer = 0; layer < options.max_layers; ++layer) {
      render::layer_view_depths(every.color, camera, layer, depth);
      render::apply_layer_shadows(
          every.color, every.shadow_terms, layer,
          render::trace_shadow_rays(scene.volume, scene.bvh, camera, surfaces, options, depth));
      every_points += count(depth);
      render::layer_view_depths(lit.color, camera, layer, depth);
      render::keep_lit_layer_points(lit.shadow_terms, layer, depth);
      lit_points += count(depth);
      render::apply_layer_shadows(
          lit.color, lit.shadow_terms, layer,
          render::trace_shadow_rays(scene.volume, scene.bvh, camera, surfaces, options, depth));
    }
    EXPECT_TRUE(same_fragments(lit.color, every.color)) << "camera " << index++;
  }
  // Some points face away from both lights, many do not.
  EXPECT_LT(lit_points, every_points - every_points / 20);
  EXPECT_GT(lit_points, every_points / 10);
}

// One LayerImage traced into frame after frame (its slots kept, as in situ) holds what a fresh
// one holds, whatever the frames before it left there: more or fewer pixels, layers per pixel
// and shadowing lights.
TEST(Layers, AReusedImageHoldsWhatAFreshOneHolds) {
  const HalfTransparentGyroid g;
  const RenderScene& scene = g.scene;
  const std::vector<render::IsoSurface>& surfaces = g.surfaces;
  struct FrameSetup {
    int side, max_layers, shadowing;
  };
  const FrameSetup frames[] = {{kSide, render::kMaxLayers, 2},
                               {kSide / 2, 2, 0},
                               {kSide, 3, 1},
                               {kSide / 3, 4, 2},
                               {kSide, render::kMaxLayers, 0}};
  render::LayerImage reused;
  for (const FrameSetup& setup : frames) {
    render::TraceOptions options;
    options.max_layers = setup.max_layers;
    options.lights.count = 1 + setup.shadowing;
    options.lights.light[0] = {render::LightKind::headlight, {}, false};
    options.lights.light[1] = {render::LightKind::point, {1.6, 2.4, 0.9}, true};
    options.lights.light[2] = {render::LightKind::directional, {-0.3, -1.0, -0.6}, true};
    const render::Camera camera = standard_cameras(setup.side, setup.side).front();
    render::LayerImage fresh;
    render::trace_layers(fresh, scene.volume, scene.bvh, camera, surfaces, options);
    render::trace_layers(reused, scene.volume, scene.bvh, camera, surfaces, options);
    const std::string name = std::to_string(setup.side) + " px, " +
                             std::to_string(setup.max_layers) + " layers, " +
                             std::to_string(setup.shadowing) + " shadowing lights";
    EXPECT_GT(fresh.color.fragments.size(), fresh.color.pixel_count() / 4) << name;
    EXPECT_TRUE(same_fragments(reused.color, fresh.color)) << name;
    ASSERT_EQ(reused.shadow_terms.size(), static_cast<std::size_t>(setup.shadowing)) << name;
    for (std::size_t j = 0; j < reused.shadow_terms.size(); ++j)
      EXPECT_TRUE(same_fragments(reused.shadow_terms[j], fresh.shadow_terms[j])) << name;
  }
}

}  // namespace
}  // namespace tetray::test
