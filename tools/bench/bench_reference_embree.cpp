#include "bench_reference_embree.hpp"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "bench_timing.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {
namespace {

using Device = std::unique_ptr<RTCDeviceTy, decltype(&rtcReleaseDevice)>;
using Scene = std::unique_ptr<RTCSceneTy, decltype(&rtcReleaseScene)>;

constexpr int kTile = 4;  // 4x4 pixels per rtcIntersect16 packet
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Huge pages asked for explicitly (Embree's default on Linux): tetray's large arrays ask for them
// too (render/core/large_array.hpp).
Device make_device(int threads) {
  const std::string config = "threads=" + std::to_string(threads) + ",hugepages=1";
  Device device(rtcNewDevice(config.c_str()), &rtcReleaseDevice);
  if (!device) throw std::runtime_error("rtcNewDevice failed");
  return device;
}

// An uncommitted scene holding the triangles through shared buffers (no copy), built as `build`
// asks (EmbreeBuild).
Scene make_scene(RTCDevice device, const TriangleSoup& triangles, EmbreeBuild build) {
  Scene scene(rtcNewScene(device), &rtcReleaseScene);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (build == EmbreeBuild::new_step) {
    rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_LOW);
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_LOW);
  }
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             triangles.xyz.data(), 0, 3 * sizeof(float), triangles.vertex_count());
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                             triangles.indices.data(), 0, 3 * sizeof(std::uint32_t),
                             triangles.triangle_count());
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  return scene;
}

struct PixelRay {
  render::Vec3f dir;
  float depth_per_t;  // view depth = t * dot(dir, forward)
};

// The image Embree's trace writes: shaded color as tetray's frame does, and depth.
struct EmbreeImage {
  render::Camera camera;
  render::CameraFrame frame;
  render::Vec3f eye;
  render::Rgb color = bench_surface().color;
  float ambient = render::TraceOptions{}.ambient;
  std::vector<float> rgba;
  std::vector<float> depth;

  explicit EmbreeImage(const render::Camera& c)
      : camera(c),
        frame(render::make_frame(c)),
        eye(static_cast<render::Vec3f>(c.eye)),
        rgba(4 * static_cast<std::size_t>(c.width) * c.height, 0.0f),
        depth(static_cast<std::size_t>(c.width) * c.height, kInfinity) {}

  PixelRay ray(int i, int j) const {
    const render::Vec3d dir = render::pixel_direction(frame, camera, i, j);
    return {static_cast<render::Vec3f>(dir), static_cast<float>(dot(dir, frame.forward))};
  }

  // Every pixel is written, hit or not, as tetray's frames are: the image is reused from
  // frame to frame.
  void background(int i, int j) {
    const std::size_t pixel = static_cast<std::size_t>(j) * camera.width + i;
    std::fill_n(&rgba[4 * pixel], 4, 0.0f);
    depth[pixel] = kInfinity;
  }

  // Two-sided Lambert headlight: color * (ambient + (1 - ambient) |cos|).
  void shade(int i, int j, const PixelRay& ray, float t, render::Vec3f normal) {
    const std::size_t pixel = static_cast<std::size_t>(j) * camera.width + i;
    const float cosine = std::abs(dot(normalize(normal), ray.dir));
    const float light = ambient + (1.0f - ambient) * cosine;
    rgba[4 * pixel + 0] = light * color.r;
    rgba[4 * pixel + 1] = light * color.g;
    rgba[4 * pixel + 2] = light * color.b;
    rgba[4 * pixel + 3] = 1.0f;
    depth[pixel] = t * ray.depth_per_t;
  }
};

void trace_single_rays(RTCScene scene, EmbreeImage& image) {
  tbb::parallel_for(tbb::blocked_range<int>(0, image.camera.height), [&](const auto& rows) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 0; i < image.camera.width; ++i) {
        const PixelRay ray = image.ray(i, j);
        RTCRayHit hit{};
        hit.ray = {image.eye.x, image.eye.y, image.eye.z, 0.0f, ray.dir.x, ray.dir.y,
                   ray.dir.z,   0.0f,        kInfinity,   ~0u,  0,         0};
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &hit);
        if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
          image.shade(i, j, ray, hit.ray.tfar, {hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z});
        } else {
          image.background(i, j);
        }
      }
  });
}

void trace_tile(RTCScene scene, RTCIntersectContext& context, EmbreeImage& image, int i0, int j0) {
  alignas(64) RTCRayHit16 packet{};
  alignas(64) int valid[16];
  PixelRay rays[16];
  for (int k = 0; k < 16; ++k) {
    const int i = i0 + k % kTile, j = j0 + k / kTile;
    valid[k] = i < image.camera.width && j < image.camera.height ? -1 : 0;
    if (!valid[k]) continue;
    rays[k] = image.ray(i, j);
    packet.ray.org_x[k] = image.eye.x;
    packet.ray.org_y[k] = image.eye.y;
    packet.ray.org_z[k] = image.eye.z;
    packet.ray.dir_x[k] = rays[k].dir.x;
    packet.ray.dir_y[k] = rays[k].dir.y;
    packet.ray.dir_z[k] = rays[k].dir.z;
    packet.ray.tfar[k] = kInfinity;
    packet.ray.mask[k] = ~0u;
    packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, scene, &context, &packet);
  for (int k = 0; k < 16; ++k) {
    if (!valid[k]) continue;
    const int i = i0 + k % kTile, j = j0 + k / kTile;
    if (packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
      image.shade(i, j, rays[k], packet.ray.tfar[k],
                  {packet.hit.Ng_x[k], packet.hit.Ng_y[k], packet.hit.Ng_z[k]});
    } else {
      image.background(i, j);
    }
  }
}

void trace_packets(RTCScene scene, EmbreeImage& image) {
  const int tile_rows = (image.camera.height + kTile - 1) / kTile;
  tbb::parallel_for(tbb::blocked_range<int>(0, tile_rows), [&](const auto& rows) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Neighbouring pixels' rays: Embree's coherent packet traversal, its fastest mode for
    // primary rays (the image is the same as with incoherent rays or rtcIntersect1).
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int row = rows.begin(); row < rows.end(); ++row)
      for (int i0 = 0; i0 < image.camera.width; i0 += kTile)
        trace_tile(scene, context, image, i0, row * kTile);
  });
}

}  // namespace

struct EmbreeReference::State {
  Device device;
  // Declared before the scene, which shares its buffers: destroyed after it.
  TriangleSoup triangles;
  Scene scene{nullptr, &rtcReleaseScene};
  EmbreeImage image;
  EmbreeBuild build;

  State(const render::Camera& camera, int threads, EmbreeBuild b)
      : device(make_device(threads)), image(camera), build(b) {}
};

EmbreeReference::EmbreeReference(const render::Camera& camera, int threads, EmbreeBuild build)
    : state_(std::make_unique<State>(camera, threads, build)) {}

EmbreeReference::~EmbreeReference() = default;

double EmbreeReference::build_ms(TriangleSoup triangles) {
  state_->scene.reset();  // before the buffers it shares go
  state_->triangles = std::move(triangles);
  state_->scene = make_scene(state_->device.get(), state_->triangles, state_->build);
  return time_ms([&] { rtcCommitScene(state_->scene.get()); });
}

double EmbreeReference::trace_ms(bool packets) {
  if (!state_->scene) throw std::logic_error("EmbreeReference traced before a scene was built");
  return time_ms([&] {
    if (packets) {
      trace_packets(state_->scene.get(), state_->image);
    } else {
      trace_single_rays(state_->scene.get(), state_->image);
    }
  });
}

const std::vector<float>& EmbreeReference::depth() const { return state_->image.depth; }

const char* embree_trace_mode(bool packets) {
  return packets ? "rtcIntersect16, coherent" : "rtcIntersect1";
}

namespace {

// Pixels whose depths differ (two misses, infinite, are the same).
std::size_t pixels_differing(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    differing += a[k] != b[k] && !(std::isinf(a[k]) && std::isinf(b[k]));
  return differing;
}

double best_build_ms(EmbreeReference& embree, const TriangleSoup& triangles) {
  return best_of_ms(kRepetitions, [&] { return embree.build_ms(triangles); });
}

double best_trace_ms(EmbreeReference& embree, bool packets) {
  embree.trace_ms(packets);
  return best_of_ms(kRepetitions, [&] { return embree.trace_ms(packets); });
}

}  // namespace

// Each figure the best of a few runs, the traces after a warm-up, every run into the same image
// (as tetray's frames are measured).
EmbreeRun trace_with_embree(const TriangleSoup& triangles, const render::Camera& camera,
                            int threads) {
  EmbreeReference embree(camera, threads);
  EmbreeRun run;
  run.build_ms = best_build_ms(embree, triangles);
  const double single_ms = best_trace_ms(embree, false);
  const std::vector<float> single_depth = embree.depth();
  const double packet_ms = best_trace_ms(embree, true);
  run.trace_ms = std::min(single_ms, packet_ms);
  run.packets = packet_ms < single_ms;
  run.depth = embree.depth();  // of the packet traces, the last ones
  run.same_depth = pixels_differing(run.depth, single_depth) == 0;
  return run;
}

EmbreeStepBuild step_build_with_embree(const TriangleSoup& triangles, const render::Camera& camera,
                                       int threads, const EmbreeRun& static_run) {
  EmbreeReference embree(camera, threads, EmbreeBuild::new_step);
  EmbreeStepBuild step;
  step.build_ms = best_build_ms(embree, triangles);
  step.trace_ms = best_trace_ms(embree, static_run.packets);
  step.depth_differs = pixels_differing(embree.depth(), static_run.depth);
  return step;
}

}  // namespace tetray::bench
