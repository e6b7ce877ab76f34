// The walk of a ray through the tets it crosses (Aman et al. 2022, §4): enter at the nearest
// boundary face, then in each tet recover the vertex opposite the entry face with three xors,
// project it, pick the exit face from the side of the ray relative to the three edges from that
// vertex (Algorithm 1), and step to the neighbour across it (Algorithms 5 and 7). Where the ray
// leaves the domain it looks for the next boundary face it enters through.
//
// The ray is projected on a 2D basis orthogonal to it (Duff et al. 2017), each vertex once per tet
// it enters. The side of the ray relative to an edge (ray_frame.hpp, ray_side) is a function of the
// directed edge alone, exactly antisymmetric, and never zero: exact ties are decided as if the ray
// moved by (e, e^2) (simulation of simplicity, Edelsbrunner and Mücke 1990), and by vertex indices
// when both ends project to one point. So every tet around an edge or vertex sees the same side,
// and a ray through a vertex or an edge crosses one face at a time, never two or none: the walk
// never loses or revisits a tet in exact arithmetic. A step bound (tets + 64) ends any ray that
// rounding could still make loop; such rays are counted (lost_rays). Where a ray crosses a face,
// its point and field value come from the ray's barycentric weights in the projected face, so the
// field is continuous from tet to tet; a second point field is interpolated with the same weights.
//
// Every decision must be computed with the same floating-point operations wherever it is made (a
// fused multiply-add in one caller and not in another once made the walk and the entry search
// disagree on a ray through a vertex), so this header is included only by render/ sources (built
// with -ffp-contract=off); other code calls walk_segments.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "render/volume/tet_volume.hpp"
#include "render/walk/boundary_faces.hpp"
#include "render/walk/empty_space.hpp"
#include "render/walk/face_adjacency.hpp"
#include "render/walk/face_crossing.hpp"
#include "render/walk/ray_frame.hpp"

namespace tetray::render {

// One tet's stretch of the ray, with the linear field at its ends.
struct WalkSegment {
  std::uint32_t tet;
  double t_in, t_out;
  double f_in, f_out;
  bool entered;        // the first tet after entering the domain (a boundary face, or the eye)
  double g_in, g_out;  // the mesh's second field (WalkMesh), or f without one
};

struct WalkCounters {
  std::uint64_t tets_visited = 0;
  std::uint64_t entries = 0;    // boundary faces entered through
  std::uint64_t lost_rays = 0;  // ended by the step bound
  std::uint64_t jumps = 0;      // over empty space (EmptySpace)

  WalkCounters& operator+=(const WalkCounters& o) {
    tets_visited += o.tets_visited;
    entries += o.entries;
    lost_rays += o.lost_rays;
    jumps += o.jumps;
    return *this;
  }
};

template <typename Layout>
struct WalkMesh {
  const TetVolume& volume;
  const FaceAdjacency<Layout>& adjacency;
  const BoundaryFaces& boundary;
  // A second point field walked along with the volume's own (per vertex of the vertex store;
  // empty: none), e.g. the field of a volume scene's isosurfaces.
  std::span<const float> second_field = {};
};

// What a walk may skip (empty_space.hpp): the volume's BVH and which tets and nodes are busy.
struct EmptySpace {
  const Bvh& bvh;
  const BusyTets& busy;
};

// Empty tets crossed in a row before a jump (next_busy_entry costs about as much as crossing a
// hundred empty tets): a few where the tet lies in a BVH node of two leaves or more without a
// busy tet, so the gap is likely long, many elsewhere (tetray-bench --volume-only, "sparse" and
// "shells").
inline constexpr int kEmptyRunInEmptyRegion = 32;
inline constexpr int kEmptyRunBeforeJump = 128;

// Rounding may put an entry a few ulps before the exit it follows.
inline double entry_slack(double t) { return 1e-9 * (1.0 + std::abs(t)); }

// Whether the walk crosses tet t without visiting it: an empty tet of a walk that skips empty
// space and runs to the end of the ray (a walk up to a finite t_max needs every exit's t).
inline bool skips_tet(const EmptySpace* empty, std::uint32_t t, double t_max) {
  return empty != nullptr && t != kBoundaryFace && !empty->busy.busy(t) &&
         t_max == std::numeric_limits<double>::infinity();
}

// Which face of the tet (entry face p0 p1 p2 counter-clockwise, new vertex p3) the ray leaves
// through, as the index of the entry-face vertex it lies across (Aman et al. 2022, Algorithm 1;
// the face opposite p_k is (p3, p_k+1, p_k+2), counter-clockwise again once p3 replaces p_k).
inline int exit_face(const ProjectedFace& face, Point2 p3, std::uint32_t v3) {
  const auto side = [&](int k) { return ray_side(p3, v3, face.point[k], face.vertex[k]); };
  if (side(0) < 0) return side(2) > 0 ? 1 : 0;
  return side(1) < 0 ? 2 : 0;
}

// Order of x among the four vertex indices of a tet.
inline int order_among(std::uint32_t x, const ProjectedFace& face, std::uint32_t v3) {
  return int(face.vertex[0] < x) + int(face.vertex[1] < x) + int(face.vertex[2] < x) + int(v3 < x);
}

// The stretch of a tet the ray starts in from t <= 0 (entry_behind) that lies at t >= 0: the
// fields at t = 0 by linear interpolation.
inline FaceCrossing clamp_to_eye(const FaceCrossing& in, const FaceCrossing& out) {
  if (!(in.t < 0)) return in;
  const double u = out.t > in.t ? std::min(1.0, -in.t / (out.t - in.t)) : 1.0;
  return {0.0, std::lerp(in.f, out.f, u), std::lerp(in.g, out.g, u)};
}

// Walks the ray from t = 0 to t_max, calling visit(const WalkSegment&) for each tet in order
// along the ray; visit returns false to stop the walk early (early ray termination).
// `eye_tet`: the tet holding the ray's origin (a camera inside the mesh, point_locate.hpp), where
// the walk starts before looking for boundary faces; kBoundaryFace: none. Tet20 only (Tet16
// ignores it: it would need the neighbour behind the eye to decode the next one).
// `empty` (Tet20 only, t_max infinite): empty tets are crossed without a visit and without the
// field at their faces; after a long run of them (kEmptyRunInEmptyRegion, kEmptyRunBeforeJump),
// or where the walk would leave the domain from one, it jumps to the next busy tet along the ray
// instead (next_busy_entry), entering it as from a boundary face (visit sees `entered`). A jump
// needs the empty stretch to be longer than twice the entry slack, so it always moves past every
// tet visited before. `candidates`: the boundary faces this ray may enter through (entry_bins.hpp);
// null: all.
template <typename Layout, typename Visit>
void walk_ray(const WalkMesh<Layout>& mesh, const RayFrame& frame, double t_max, Visit&& visit,
              WalkCounters& counters, std::uint32_t eye_tet = kBoundaryFace,
              const EmptySpace* empty = nullptr, const EntryCandidates* candidates = nullptr) {
  if constexpr (!std::is_same_v<Layout, Tet20>) empty = nullptr;  // a jump needs Tet20
  const std::uint64_t step_bound = mesh.volume.tets.size() + 64;
  std::uint64_t steps = 0;
  double t_from = 0;
  EntryCursor cursor;
  std::optional<FaceEntry> entry;
  if constexpr (std::is_same_v<Layout, Tet20>) {
    if (eye_tet != kBoundaryFace)
      entry = entry_behind(mesh.volume, frame, eye_tet, mesh.second_field);
  }
  const auto next_boundary_entry = [&] {
    return next_entry(mesh.volume, mesh.boundary, frame, t_from, cursor, mesh.second_field,
                      candidates);
  };
  if (!entry) entry = next_boundary_entry();
  for (; entry; entry = next_boundary_entry()) {
    if (entry->crossing.t > t_max) return;
    if (entry->face != kBoundaryFace) cursor = {entry->crossing.t, entry->face, true};
    ++counters.entries;
    ProjectedFace face = entry->projected;
    FaceCrossing in = entry->crossing;
    std::uint32_t tet = entry->tet;
    std::uint32_t previous = kBoundaryFace;
    bool entered = true;
    // After empty tets the field at the entry face is computed only when a busy tet needs it;
    // t_known is the last ray parameter computed, where the empty tets began.
    bool in_known = true;
    double t_known = in.t;
    int empty_run = 0;  // empty tets in a row just crossed
    for (;;) {
      if (++steps > step_bound) {
        ++counters.lost_rays;
        return;
      }
      ++counters.tets_visited;
      const bool skip = skips_tet(empty, tet, t_max);
      if (!skip && !in_known) {
        in = cross_face(mesh.volume, frame, face, mesh.second_field);
        in.t = std::max(in.t, t_known);
        in_known = true;
      }
      const Layout& cell = mesh.adjacency.tets[tet];
      const std::uint32_t v3 = face.vertex[0] ^ face.vertex[1] ^ face.vertex[2] ^ cell.vertex_xor;
      const Point2 p3 = frame.project(vertex_position(mesh.volume, v3));
      const int k = exit_face(face, p3, v3);
      const std::uint32_t next =
          cell.next(previous, order_among(v3, face, v3), order_among(face.vertex[k], face, v3));
      face.vertex[k] = v3;
      face.point[k] = p3;
      if (skip) {
        // Nothing to gather here: jump over a long gap to the next busy tet (where the walk
        // would leave the domain, or after a long run of empty tets into another), else go on.
        const bool leaving = next == kBoundaryFace;
        ++empty_run;
        const int run_before_jump =
            empty->busy.in_empty_region(tet) ? kEmptyRunInEmptyRegion : kEmptyRunBeforeJump;
        if (leaving || (empty_run >= run_before_jump && skips_tet(empty, next, t_max))) {
          const double t_out = std::max(cross_face(mesh.volume, frame, face).t, t_known);
          // Every tet visited before began at or before t_known: the jump cannot meet one again.
          if (t_out - t_known > 2 * entry_slack(t_out)) {
            const std::optional<FaceEntry> jump =
                next_busy_entry(mesh.volume, empty->bvh, empty->busy, frame,
                                t_out - entry_slack(t_out), mesh.second_field);
            if (!jump) return;
            ++counters.jumps;
            face = jump->projected;
            in = jump->crossing;
            t_known = in.t;
            in_known = true;
            tet = jump->tet;
            previous = kBoundaryFace;
            entered = true;
            empty_run = 0;
            continue;
          }
          if (leaving) {
            t_from = t_out - entry_slack(t_out);
            break;
          }
        }
        previous = tet;
        tet = next;
        in_known = false;
        continue;
      }
      empty_run = 0;
      FaceCrossing out = cross_face(mesh.volume, frame, face, mesh.second_field);
      in = clamp_to_eye(in, out);
      out.t = std::max(out.t, in.t);
      const WalkSegment segment{tet, in.t, out.t, in.f, out.f, entered, in.g, out.g};
      if (!visit(segment) || out.t >= t_max) return;
      entered = false;
      t_known = out.t;
      if (next == kBoundaryFace) {
        t_from = out.t - entry_slack(out.t);
        break;
      }
      previous = tet;
      tet = next;
      in = out;
    }
  }
}

// The segments of walk_ray, at most `max_segments` of them, for callers outside render/.
template <typename Layout>
std::vector<WalkSegment> walk_segments(const WalkMesh<Layout>& mesh, const RayFrame& frame,
                                       double t_max, std::size_t max_segments,
                                       WalkCounters& counters);

// Walks every pixel's ray of a frame (origin `eye` in local coordinates, directions from
// `directions`, one per pixel) without doing anything in the tets: the cost of the walk alone,
// for the benchmark. Parallel over pixels in the calling oneTBB arena.
template <typename Layout>
WalkCounters walk_rays(const WalkMesh<Layout>& mesh, Vec3d eye, std::span<const Vec3d> directions);

extern template WalkCounters walk_rays<Tet20>(const WalkMesh<Tet20>&, Vec3d,
                                              std::span<const Vec3d>);
extern template WalkCounters walk_rays<Tet16>(const WalkMesh<Tet16>&, Vec3d,
                                              std::span<const Vec3d>);

extern template std::vector<WalkSegment> walk_segments<Tet20>(const WalkMesh<Tet20>&,
                                                              const RayFrame&, double, std::size_t,
                                                              WalkCounters&);
extern template std::vector<WalkSegment> walk_segments<Tet16>(const WalkMesh<Tet16>&,
                                                              const RayFrame&, double, std::size_t,
                                                              WalkCounters&);

}  // namespace tetray::render
