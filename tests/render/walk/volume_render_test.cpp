// Volume rendering against analytic answers: one stretch's integral against the closed forms of
// emission-absorption with constant and linear extinction and color; whole images of a box with
// a constant field (Beer-Lambert) and a linear field (closed-form optical depth and emission);
// and a jittered box with a random field against dense double-precision sampling along the
// brute-force tets; early termination's effect is bounded by its threshold. Surfaces along the
// walk: where the walk meets the isosurfaces of a second field against the double-precision
// reference, and a constant volume in front of an opaque or a transparent plane against the
// closed form (Beer-Lambert up to the plane, the lit plane, the volume behind it).
#include "render/walk/volume_render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/walk/segment_integral.hpp"
#include "render/walk/surface_crossing.hpp"
#include "render/walk/tet_walk.hpp"
#include "support/reference_camera.hpp"
#include "support/reference_intersector.hpp"
#include "walk_meshes.hpp"

namespace tetray::test {
namespace {

// Linear RGB ramps of our own, so expected colors are closed forms.
const render::Colormap kBlackToWhite{{0, 0, 0, 1, 1, 1}};
const render::Colormap kOrange{{1.0f, 0.5f, 0.25f, 1.0f, 0.5f, 0.25f}};

render::TransferFunction transfer(const render::Colormap& map, double lo, double hi,
                                  std::vector<render::OpacityPoint> opacity,
                                  double unit_distance = 1) {
  return {&map, lo, hi, std::move(opacity), unit_distance};
}

TEST(SegmentIntegral, ConstantIsBeerLambert) {
  const auto tf = transfer(kOrange, 0, 1, {{0, 1.7}}, 0.5);
  const render::BreakpointTable breaks(tf);
  for (double length : {1e-6, 0.01, 0.3, 2.0, 9.0}) {
    const render::Gathered g = render::integrate_segment(tf, breaks, length, 0.4, 0.4);
    const double alpha = 1 - std::exp(-1.7 / 0.5 * length);
    EXPECT_NEAR(g.transmittance, 1 - alpha, 1e-15);
    EXPECT_NEAR(g.color[0], 1.0 * alpha, 1e-9 * alpha);
    EXPECT_NEAR(g.color[1], 0.5 * alpha, 1e-9 * alpha);
  }
}

TEST(SegmentIntegral, LinearExtinctionAndLinearColorMatchClosedForms) {
  // Extinction linear in the value, from 0.2 at f = 0 to 3.2 at f = 1; constant color.
  const auto ramp = transfer(kOrange, 0, 1, {{0, 0.2}, {1, 3.2}});
  for (double length : {0.01, 0.7, 4.0}) {
    const render::Gathered g =
        render::integrate_segment(ramp, render::BreakpointTable(ramp), length, 0.0, 1.0);
    const double depth = 0.5 * (0.2 + 3.2) * length;
    EXPECT_NEAR(g.transmittance, std::exp(-depth), 1e-15);
    EXPECT_NEAR(g.color[2], 0.25 * (1 - std::exp(-depth)), 1e-10);
  }
  // Color linear in the value, black at f = 0 to white at f = 1; constant extinction k:
  // C = int_0^L (t / L) k exp(-k t) dt = (1 - exp(-kL) (1 + kL)) / (kL).
  const double k = 1.3;
  const auto gray = transfer(kBlackToWhite, 0, 1, {{0, k}});
  for (double length : {0.05, 1.0, 6.0}) {
    const render::Gathered g =
        render::integrate_segment(gray, render::BreakpointTable(gray), length, 0.0, 1.0);
    const double kl = k * length;
    EXPECT_NEAR(g.color[1], (1 - std::exp(-kl) * (1 + kl)) / kl, 1e-10) << length;
  }
}

TEST(SegmentIntegral, BreakpointsSplitTheStretch) {
  // A tent: extinction 0 at f = 0 and f = 1, 4 at f = 0.5. Over f 0 -> 1 along length L the
  // optical depth is the tent's mean, 2 L; a straight line through the kink would give 0.
  const auto tent = transfer(kOrange, 0, 1, {{0, 0}, {0.5, 4}, {1, 0}});
  for (double from : {0.0, 1.0}) {
    const render::Gathered g =
        render::integrate_segment(tent, render::BreakpointTable(tent), 0.5, from, 1.0 - from);
    EXPECT_NEAR(g.transmittance, std::exp(-1.0), 1e-15);
  }
}

struct VolumeScene {
  RenderScene scene;
  render::WalkStructure walk;
  explicit VolumeScene(const BoxMesh& mesh, const ScalarFunction& f)
      : scene(load_scene(mesh.points, mesh.tets, sample_field(mesh.points, f))),
        walk(render::build_walk_structure(scene.volume)) {}
};

// The ray's stretch inside [-1, 1]^3.
std::pair<double, double> box_chord(Vec3d o, Vec3d d) {
  double t0 = 0, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    double lo = (-1 - o[a]) / d[a], hi = (1 - o[a]) / d[a];
    if (lo > hi) std::swap(lo, hi);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, hi);
  }
  return {t0, std::max(t0, t1)};
}

render::Camera box_camera() {
  const int side = scaled_side(48);
  return look_at({0.6, -0.9, 4.5}, {0, 0.1, 0}, 38, side, side);
}

// Per pixel of `camera` (by default onto the box from outside): the fragments' merged color
// against `expected(o, d, t0, t1) -> {rgb, alpha}`.
template <typename Expected>
void expect_box_image(const VolumeScene& v, const render::VolumeRenderOptions& options,
                      Expected&& expected, double tolerance,
                      const render::Camera& camera = box_camera()) {
  const int side = camera.width;
  render::VolumeFragmentImage fragments =
      render::render_volume(v.scene.volume, v.walk, camera, options);
  const render::Framebuffer image = render::resolve(fragments);
  const ReferenceCamera reference(camera);
  int covered = 0;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const Vec3d d = reference.pixel_direction(i, j);
      const auto [t0, t1] = box_chord(reference.eye(), d);
      const std::array<double, 4> want = expected(reference.eye(), d, t0, t1);
      const float* got = &image.rgba[4 * image.index(i, j)];
      for (int c = 0; c < 4; ++c) {
        ASSERT_NEAR(got[c], want[c], tolerance) << "pixel " << i << ", " << j << " channel " << c;
      }
      covered += t1 - t0 > 0.01;
    }
  }
  EXPECT_GT(covered, side * side / 4);
}

TEST(VolumeRender, ConstantFieldIsBeerLambert) {
  const VolumeScene v(jittered_box(4, 0.15), [](Vec3d) { return 0.3; });
  render::VolumeRenderOptions options;
  options.transfer = transfer(kOrange, 0, 1, {{0, 0.8}});
  options.termination = 1;
  expect_box_image(
      v, options,
      [](Vec3d, Vec3d, double t0, double t1) {
        const double alpha = 1 - std::exp(-0.8 * (t1 - t0));
        return std::array<double, 4>{1.0 * alpha, 0.5 * alpha, 0.25 * alpha, alpha};
      },
      2e-6);
}

TEST(VolumeRender, LinearFieldMatchesTheClosedForm) {
  // f = z; extinction (z + 1) / 2 per unit length from the ramp; color from black at z = -1 to
  // white at z = 1. Along the ray z = z0 + dz t: optical depth from t0 to t is
  // ((z0 + 1)(t - t0) + dz (t^2 - t0^2) / 2) / 2, and the emission has no closed form simpler
  // than its integral, so it is summed here with 20000 midpoints (error ~1e-9).
  const VolumeScene v(jittered_box(4, 0.15), [](Vec3d x) { return x.z; });
  render::VolumeRenderOptions options;
  options.transfer = transfer(kBlackToWhite, -1, 1, {{-1, 0}, {1, 1}});
  options.termination = 1;
  expect_box_image(
      v, options,
      [](Vec3d o, Vec3d d, double t0, double t1) {
        const auto depth = [&](double t) {
          return ((o.z + 1) * (t - t0) + d.z * (t * t - t0 * t0) / 2) / 2;
        };
        const int n = 20000;
        const double h = (t1 - t0) / n;
        double emitted = 0;
        for (int k = 0; k < n; ++k) {
          const double t = t0 + (k + 0.5) * h;
          const double z = o.z + d.z * t;
          emitted += h * (z + 1) / 2 * (z + 1) / 2 * std::exp(-depth(t));
        }
        const double alpha = 1 - std::exp(-depth(t1));
        return std::array<double, 4>{emitted, emitted, emitted, alpha};
      },
      2e-6);
}

// Dense sampling of the brute-force tets' linear field along one ray, in double precision.
std::array<double, 4> densely_sampled(const render::TetVolume& volume,
                                      const render::TransferFunction& tf, Vec3d eye_local,
                                      Vec3d d) {
  const std::vector<CrossedTet> tets = crossed_by_brute_force(volume, eye_local, d, 0.0);
  double color[3] = {0, 0, 0}, transmittance = 1;
  for (const CrossedTet& c : tets) {
    const int n = 4000;
    const double h = (c.t_out - c.t_in) / n;
    for (int k = 0; k < n; ++k) {
      const double f = c.f_in + (k + 0.5) / n * (c.f_out - c.f_in);
      const render::TransferFunction::Sample s = tf.at(f);
      const double step = std::exp(-s.extinction * h);
      for (int ch = 0; ch < 3; ++ch) color[ch] += transmittance * s.color[ch] * (1 - step);
      transmittance *= step;
    }
  }
  return {color[0], color[1], color[2], 1 - transmittance};
}

TEST(VolumeRender, RandomFieldMatchesDenseSampling) {
  const BoxMesh mesh = jittered_box(3, 0.2);
  const VolumeScene v(mesh, [](Vec3d) { return 0.0; });
  RenderScene random = load_scene(mesh.points, mesh.tets, random_field(mesh.point_count(), 3));
  const render::WalkStructure walk = render::build_walk_structure(random.volume);
  render::VolumeRenderOptions options;
  options.transfer = transfer(kBlackToWhite, -1, 1, {{-1, 0.1}, {-0.2, 2.5}, {0.3, 0.0}, {1, 1.5}});
  options.termination = 1;
  const int side = 12 / (kSanitizerSlowdown > 1 ? 2 : 1);
  const render::Camera camera = look_at({-2.2, 1.4, 3.1}, {0.1, 0, 0}, 40, side, side);
  render::VolumeFragmentImage fragments =
      render::render_volume(random.volume, walk, camera, options);
  const render::Framebuffer image = render::resolve(fragments);
  const ReferenceCamera reference(camera);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const std::array<double, 4> want =
          densely_sampled(random.volume, options.transfer, reference.eye() - random.volume.origin,
                          reference.pixel_direction(i, j));
      for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(image.rgba[4 * image.index(i, j) + c], want[c], 2e-5)
            << "pixel " << i << ", " << j << " channel " << c;
      }
    }
  }
}

TEST(VolumeRender, EarlyTerminationStopsAtTheThreshold) {
  const VolumeScene v(jittered_box(6, 0.15), [](Vec3d) { return 0.3; });
  render::VolumeRenderOptions options;
  options.transfer = transfer(kOrange, 0, 1, {{0, 6.0}});
  const render::Camera camera = look_at({0.2, 0.1, 4}, {0, 0, 0}, 20, 16, 16);
  render::VolumeRenderStats full, early;
  options.termination = 1;
  render::VolumeFragmentImage all =
      render::render_volume(v.scene.volume, v.walk, camera, options, &full);
  options.termination = 0.95;
  render::VolumeFragmentImage cut =
      render::render_volume(v.scene.volume, v.walk, camera, options, &early);
  EXPECT_LT(early.tets_visited, full.tets_visited / 2);
  EXPECT_GT(early.terminated_runs, 0u);
  const render::Framebuffer a = render::resolve(all), b = render::resolve(cut);
  for (std::size_t p = 0; p < a.pixel_count(); ++p) {
    if (b.rgba[4 * p + 3] == 0) continue;
    EXPECT_GE(b.rgba[4 * p + 3], 0.95f);
    EXPECT_NEAR(a.rgba[4 * p + 3], b.rgba[4 * p + 3], 0.05);
  }
}

TEST(VolumeSurfaces, CrossingsMatchTheReference) {
  // The volume's field is one random field, the surfaces' another: the walk carries both.
  const BoxMesh mesh = jittered_box(4, 0.2);
  const std::vector<double> g = random_field(mesh.point_count(), 5);
  const RenderScene scene = load_scene(mesh.points, mesh.tets, random_field(mesh.point_count(), 9));
  const RenderScene of_g = load_scene(mesh.points, mesh.tets, g);
  const std::vector<float> second = per_vertex(scene.volume, g);
  const render::WalkStructure walk = render::build_walk_structure(scene.volume);
  const render::WalkMesh<render::Tet20> walk_mesh{scene.volume, walk.adjacency, walk.boundary,
                                                  second};
  const std::vector<double> isovalues = {-0.3, 0.1, 0.45};
  const std::vector<render::IsoSurface> surfaces = make_surfaces(isovalues);
  const ReferenceIntersector reference(of_g.volume, isovalues);
  const int side = scaled_side(32);
  const ReferenceCamera camera(look_at({-2.4, 1.3, 3.0}, {0.1, 0, 0}, 40, side, side));
  int compared = 0;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const Vec3d d = camera.pixel_direction(i, j);
      const ReferenceLayers want = reference.trace_layers(camera, d);
      if (want.isopolygon_edge_distance < 2 * kGrazingDistance ||
          want.closest_layers < 2 * kGrazingDistance)
        continue;
      render::WalkCounters counters;
      std::vector<std::pair<double, int>> got;
      for (const render::WalkSegment& s :
           render::walk_segments(walk_mesh, render::RayFrame(camera.eye() - scene.volume.origin, d),
                                 std::numeric_limits<double>::infinity(), 1 << 20, counters)) {
        render::SurfaceCrossing c[render::kMaxIsovalues];
        const int n = render::surface_crossings(surfaces, s.g_in, s.g_out, c);
        for (int k = 0; k < n; ++k)
          got.emplace_back(std::lerp(s.t_in, s.t_out, c[k].u), c[k].surface);
      }
      ASSERT_EQ(got.size(), want.layers.size()) << "pixel " << i << ", " << j;
      for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_NEAR(got[k].first, want.layers[k].t, 1e-6) << "pixel " << i << ", " << j;
        EXPECT_EQ(got[k].second, want.layers[k].surface) << "pixel " << i << ", " << j;
      }
      compared += !got.empty();
    }
  }
  EXPECT_GT(compared, side * side / 4);
}

// The box's constant volume (extinction k, orange) and the plane x = `plane` of a lit surface
// (headlight, |cos| = |d.x|) along the ray's chord [t0, t1].
std::array<double, 4> volume_and_plane(Vec3d o, Vec3d d, double t0, double t1, double k,
                                       double plane, render::Rgb rgb, double opacity,
                                       double ambient) {
  const double ts = (plane - o.x) / d.x;
  const bool crossed = ts > t0 && ts < t1;
  const double t_front = std::exp(-k * ((crossed ? ts : t1) - t0));
  std::array<double, 4> c = {1.0 * (1 - t_front), 0.5 * (1 - t_front), 0.25 * (1 - t_front),
                             1 - t_front};
  if (!crossed) return c;
  const double light = ambient + (1 - ambient) * std::abs(d.x);
  const double back = 1 - std::exp(-k * (t1 - ts));  // the volume behind the plane
  const double surface[3] = {rgb.r, rgb.g, rgb.b};
  const double volume[3] = {1.0, 0.5, 0.25};
  for (int ch = 0; ch < 3; ++ch)
    c[ch] += t_front * (opacity * light * surface[ch] + (1 - opacity) * back * volume[ch]);
  c[3] += t_front * (opacity + (1 - opacity) * back);
  return c;
}

TEST(VolumeSurfaces, ConstantVolumeBeforeAPlaneIsBeerLambert) {
  // Volume: constant field, extinction 0.8, orange. Surface: x = 0.2 of the field g = x. Seen
  // from outside the box, and from an eye inside it, whose rays start in the eye's tet.
  const BoxMesh mesh = jittered_box(4, 0.15);
  const VolumeScene v(mesh, [](Vec3d) { return 0.3; });
  const std::vector<double> g = sample_field(mesh.points, [](Vec3d x) { return x.x; });
  const std::vector<float> second = per_vertex(v.scene.volume, g);
  const double k = 0.8, ambient = 0.25, plane = 0.2;
  const render::Rgb rgb{0.2f, 0.6f, 1.0f};
  for (const float opacity : {1.0f, 0.4f}) {
    render::VolumeRenderOptions options;
    options.transfer = transfer(kOrange, 0, 1, {{0, k}});
    options.termination = 1;
    options.surfaces = {{static_cast<float>(plane), rgb, opacity}};
    options.surface_field = second;
    options.ambient = ambient;
    const auto expected = [&](Vec3d o, Vec3d d, double t0, double t1) {
      return volume_and_plane(o, d, t0, t1, k, plane, rgb, opacity, ambient);
    };
    expect_box_image(v, options, expected, 2e-6);
    const render::Camera inside =
        look_at({-0.35, 0.1, 0.3}, {1, 0.4, -0.5}, 70, scaled_side(40), scaled_side(40));
    options.eye_tet = render::locate_eye(v.scene.volume, v.scene.bvh, inside);
    ASSERT_NE(options.eye_tet, render::kBoundaryFace);
    expect_box_image(v, options, expected, 2e-6, inside);
  }
}

}  // namespace
}  // namespace tetray::test
