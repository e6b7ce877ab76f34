#include "render/walk/volume_render.hpp"

#include <oneapi/tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "render/walk/entry_bins.hpp"
#include "render/walk/fixed_step.hpp"
#include "render/walk/point_locate.hpp"
#include "render/walk/segment_integral.hpp"
#include "render/walk/surface_crossing.hpp"
#include "render/walk/tet_walk.hpp"

namespace tetray::render {
namespace {

struct RowOutput {
  std::vector<VolumeFragment> fragments;
  std::vector<std::uint32_t> counts;  // per pixel of the row
  VolumeRenderStats stats;
};

// What one ray gathers: a fragment per run of tets between a boundary entry and the next exit,
// from the first stretch with any opacity, with the surfaces it crosses laid in between.
class RayGatherer {
 public:
  RayGatherer(const TetVolume& volume, const VolumeRenderOptions& options,
              const BreakpointTable& breakpoints, Vec3d direction, double depth_per_t,
              std::vector<VolumeFragment>& out)
      : volume_(volume),
        options_(options),
        breakpoints_(breakpoints),
        direction_(direction),
        depth_per_t_(depth_per_t),
        out_(out),
        sampler_(options.transfer, options.sample_step) {}

  // Gathers one tet's stretch; false once the ray's opacity reached the termination.
  bool add(const WalkSegment& s) {
    if (s.entered) {
      close_run();
      open_ = true;
      visible_ = false;
      run_ = {};
      fragment_ = {};
      sampler_.restart(s.t_in);
    }
    SurfaceCrossing crossings[kMaxIsovalues];
    const int n = surface_crossings(options_.surfaces, s.g_in, s.g_out, crossings);
    // The volume up to each crossing, the surface, and on from there.
    double u0 = 0;
    for (int k = 0; k < n; ++k) {
      volume_piece(s, u0, crossings[k].u);
      u0 = crossings[k].u;
      const double light =
          surface_light(volume_, options_.surface_field, s.tet, direction_, options_.ambient);
      take(surface_layer(options_.surfaces[static_cast<std::size_t>(crossings[k].surface)], light),
           std::lerp(s.t_in, s.t_out, u0), s.tet);
    }
    volume_piece(s, u0, 1);
    fragment_.depth_out = static_cast<float>(s.t_out * depth_per_t_);
    const double opacity = 1.0 - transmittance_ * run_.transmittance;
    if (opacity < options_.termination) return true;
    terminated_ = true;
    close_run();
    return false;
  }

  void close_run() {
    if (!open_) return;
    open_ = false;
    for (int c = 0; c < 3; ++c) fragment_.rgba[c] = run_.color[c];
    fragment_.rgba[3] = 1.0 - run_.transmittance;
    transmittance_ *= run_.transmittance;
    if (visible_) out_.push_back(fragment_);
  }

  bool terminated() const { return terminated_; }

 private:
  // The volume over [u0, u1] of the stretch s, where the field is linear in u (std::lerp is
  // exact at u = 0 and 1: a stretch no surface cuts is integrated as it is).
  void volume_piece(const WalkSegment& s, double u0, double u1) {
    const double t0 = std::lerp(s.t_in, s.t_out, u0), t1 = std::lerp(s.t_in, s.t_out, u1);
    const double f0 = std::lerp(s.f_in, s.f_out, u0), f1 = std::lerp(s.f_in, s.f_out, u1);
    take(options_.sample_step > 0
             ? sampler_.stretch(t0, t1, f0, f1)
             : integrate_segment(options_.transfer, breakpoints_, t1 - t0, f0, f1),
         t0, s.tet);
  }

  // Lays g (starting at ray parameter t_in, in `tet`) behind the run so far.
  void take(const Gathered& g, double t_in, std::uint32_t tet) {
    // The fragment starts where the ray first meets opacity, which does not depend on where
    // a rank's sub-domain begins.
    if (!visible_ && g.transmittance < 1) {
      visible_ = true;
      fragment_.depth_in = static_cast<float>(t_in * depth_per_t_);
      fragment_.key = volume_.tet_ids[tet];
    }
    run_.then(g);
  }

  const TetVolume& volume_;
  const VolumeRenderOptions& options_;
  const BreakpointTable& breakpoints_;
  Vec3d direction_;  // unit, local
  double depth_per_t_;
  std::vector<VolumeFragment>& out_;
  FixedStepSampler sampler_;  // used when options_.sample_step > 0
  bool open_ = false, visible_ = false, terminated_ = false;
  Gathered run_;
  VolumeFragment fragment_;
  double transmittance_ = 1;  // of the runs before this one
};

}  // namespace

WalkStructure build_walk_structure(const TetVolume& volume) {
  WalkStructure walk;
  walk.adjacency = build_face_adjacency<Tet20>(volume);
  walk.boundary = build_boundary_faces(volume, walk.adjacency.boundary);
  return walk;
}

std::uint32_t locate_eye(const TetVolume& volume, const Bvh& bvh, const Camera& camera) {
  const std::optional<PointLocation> at = locate_point(volume, bvh, camera.eye - volume.origin);
  return at ? at->tet : kBoundaryFace;
}

VolumeFragmentImage render_volume(const TetVolume& volume, const WalkStructure& walk,
                                  const Camera& camera, const VolumeRenderOptions& options,
                                  VolumeRenderStats* stats) {
  const CameraFrame frame = make_frame(camera);
  const BreakpointTable breakpoints(options.transfer);
  const WalkMesh<Tet20> mesh{volume, walk.adjacency, walk.boundary, options.surface_field};
  const Vec3d eye = camera.eye - volume.origin;
  const bool skip = options.bvh != nullptr && !(options.sample_step > 0);
  const BusyTets busy = skip ? find_busy_tets(volume, *options.bvh, options.transfer,
                                              options.surfaces, options.surface_field)
                             : BusyTets{};
  std::optional<EmptySpace> empty;
  if (skip) empty.emplace(EmptySpace{*options.bvh, busy});
  const EntryBins bins = bin_entry_faces(volume, walk.boundary, camera);
  std::vector<RowOutput> rows(static_cast<std::size_t>(camera.height));
  tbb::parallel_for(0, camera.height, [&](int j) {
    RowOutput& row = rows[static_cast<std::size_t>(j)];
    row.counts.resize(static_cast<std::size_t>(camera.width));
    for (int i = 0; i < camera.width; ++i) {
      // A ray that starts outside the mesh and has no face to enter through sees nothing.
      const EntryCandidates candidates = bins.usable() ? bins.at(i, j) : EntryCandidates{};
      if (bins.usable() && options.eye_tet == kBoundaryFace && candidates.tile.empty() &&
          candidates.everywhere.empty())
        continue;
      const Vec3d direction = pixel_direction(frame, camera, i, j);
      const RayFrame ray(eye, direction);
      const std::size_t before = row.fragments.size();
      RayGatherer gather(volume, options, breakpoints, ray.direction,
                         dot(ray.direction, frame.forward), row.fragments);
      WalkCounters counters;
      walk_ray(
          mesh, ray, std::numeric_limits<double>::infinity(),
          [&](const WalkSegment& s) { return gather.add(s); }, counters, options.eye_tet,
          empty ? &*empty : nullptr, bins.usable() ? &candidates : nullptr);
      gather.close_run();
      row.counts[static_cast<std::size_t>(i)] =
          static_cast<std::uint32_t>(row.fragments.size() - before);
      row.stats.tets_visited += counters.tets_visited;
      row.stats.entries += counters.entries;
      row.stats.lost_rays += counters.lost_rays;
      row.stats.jumps += counters.jumps;
      row.stats.terminated_runs += gather.terminated();
    }
  });
  VolumeFragmentImage image;
  image.width = camera.width;
  image.height = camera.height;
  image.begin.reserve(image.pixel_count() + 1);
  image.begin.push_back(0);
  VolumeRenderStats total;
  for (RowOutput& row : rows) {
    for (std::uint32_t n : row.counts) image.begin.push_back(image.begin.back() + n);
    image.fragments.insert(image.fragments.end(), row.fragments.begin(), row.fragments.end());
    total.tets_visited += row.stats.tets_visited;
    total.entries += row.stats.entries;
    total.lost_rays += row.stats.lost_rays;
    total.jumps += row.stats.jumps;
    total.terminated_runs += row.stats.terminated_runs;
  }
  total.rays = image.pixel_count();
  total.busy_tets = skip ? busy.busy_count : volume.tets.size();
  if (stats != nullptr) *stats = total;
  return image;
}

}  // namespace tetray::render
