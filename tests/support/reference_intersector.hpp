// The brute-force double-precision reference for tetray's images: every pixel ray is tested
// against every tet of the volume (the renderer's own float data, read in double), nearest hit
// over all tets and isovalues. It shares only the tet data with the renderer: its rays come from
// its own camera (reference_camera.hpp). Slow by design: for meshes of a few thousand tets.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "render/volume/tet_volume.hpp"
#include "support/reference_camera.hpp"
#include "support/reference_clip.hpp"
#include "support/reference_tet.hpp"

namespace tetray::test {

// Relative distances below this make a ray "grazing": float rounding in the renderer may
// decide either way, so comparisons exempt it.
inline constexpr double kGrazingDistance = 1e-6;

struct ReferenceHit {
  static constexpr double kNone = std::numeric_limits<double>::infinity();

  bool hit = false;
  double t = kNone;      // ray parameter (unit direction) of the nearest hit
  double depth = kNone;  // view-axis depth of docs/architecture.md §3
  std::uint32_t tet_id = 0;
  int surface = -1;    // index of the isovalue hit
  double abs_cos = 0;  // |cos| between the ray and the surface normal
  // Depth of the nearest hit on any other isopolygon (a near tie makes the hit id ambiguous).
  double second_depth = kNone;
  // Relative (to length_scale) distances from the ray, up to just past the hit (or through
  // the whole mesh on a miss), to the nearest isopolygon edge and the nearest tet edge.
  // Exact below 2 kGrazingDistance; a larger value only says the true one is larger too.
  double isopolygon_edge_distance = kNone;
  double tet_edge_distance = kNone;
  double length_scale = 0;  // float rounding in the renderer scales with this length
  // With a clip region: the smallest relative distance from the region's planes of the hits
  // up to the nearest kept one (all hits on a miss); near a plane, keep or discard is rounding.
  double clip_boundary_distance = kNone;
};

// A shadow ray of the reference: whether a surface lies on the segment, and how close the
// decision is to rounding.
struct ReferenceShadow {
  bool blocked = false;
  double nearest_t = ReferenceHit::kNone;  // of a blocking hit
  // Relative (to the intersector's length scale) distances from the segment to the nearest
  // isopolygon edge, and of its hits from a clip plane: below the renderer's rounding either
  // answer is right.
  double isopolygon_edge_distance = ReferenceHit::kNone;
  double clip_boundary_distance = ReferenceHit::kNone;
};

// Every hit of a ray inside the clip region, nearest first: the layers of transparent surfaces
// (Wald et al. 2007, §8.5), with how close the ray comes to deciding them by rounding.
struct ReferenceLayers {
  struct Layer {
    double t = 0;
    int surface = -1;  // index of the isovalue hit
  };
  std::vector<Layer> layers;
  // Relative (to length_scale) distances over the whole ray: to the nearest isopolygon edge and
  // of any hit from a clip plane; and between the two closest consecutive layers (their order
  // is rounding below the renderer's precision).
  double isopolygon_edge_distance = ReferenceHit::kNone;
  double clip_boundary_distance = ReferenceHit::kNone;
  double closest_layers = ReferenceHit::kNone;
  double length_scale = 0;
};

// Copies the tets of `volume` to double precision with their caller ids.
std::vector<ReferenceTet> reference_tets(const render::TetVolume& volume);

class ReferenceIntersector {
 public:
  // Only hits in the clip region count (with the default region: all).
  ReferenceIntersector(const render::TetVolume& volume, std::vector<double> isovalues,
                       const render::ClipRegion& clip = {});

  ReferenceHit trace_ray(const ReferenceCamera& camera, Vec3d direction) const;
  ReferenceLayers trace_layers(const ReferenceCamera& camera, Vec3d direction) const;
  // One ReferenceHit per pixel, row-major from the top-left (Framebuffer::index), computed in
  // parallel over rows.
  std::vector<ReferenceHit> trace_image(const render::Camera& camera) const;
  // The segment from `from` (local coordinates) along the unit `direction` over (t_min, t_max),
  // against every isosurface inside the clip region.
  ReferenceShadow shadow_ray(Vec3d from, Vec3d direction, double t_min, double t_max) const;
  double length_scale() const { return extent_; }

 private:
  Vec3d origin_;
  double extent_;  // diagonal of the tets' bounding box
  std::vector<ReferenceTet> tets_;
  std::vector<double> isovalues_;
  ReferenceClip clip_;
  bool clipped_ = false;
};

// Decides whether a ray's exact path (t >= 0) passes through a point of some tet where the
// piecewise-linear field is below `level`: the rays that must hit a closed level set.
class BelowLevelProbe {
 public:
  BelowLevelProbe(const render::TetVolume& volume, double level);
  bool passes_below(Vec3d eye, Vec3d direction) const;

 private:
  Vec3d origin_;
  double level_;
  std::vector<ReferenceTet> tets_;  // only those with a vertex below the level
};

}  // namespace tetray::test
