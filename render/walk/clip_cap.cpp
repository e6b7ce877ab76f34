#include "render/walk/clip_cap.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "render/scene/shade.hpp"
#include "render/walk/point_locate.hpp"

namespace tetray::render {
namespace {

// One side of the region, dot(normal, x) <= offset in local coordinates, normal outward.
struct HalfSpace {
  Vec3d normal;
  double offset;
};

// The region's sides, made once per frame (a cap asks for every pixel's entry).
struct RegionSides {
  HalfSpace side[6 + kMaxClipPlanes];
  int count = 0;
};

RegionSides region_sides(const ClipRegion& region, Vec3d origin) {
  RegionSides sides;
  if (region.has_box) {
    const Vec3d lo = region.box_lo - origin, hi = region.box_hi - origin;
    for (int a = 0; a < 3; ++a) {
      Vec3d n{0, 0, 0};
      n[a] = 1;
      sides.side[sides.count++] = {n, hi[a]};
      n[a] = -1;
      sides.side[sides.count++] = {n, -lo[a]};
    }
  }
  for (int k = 0; k < std::min(region.plane_count, kMaxClipPlanes); ++k) {
    const Vec3d n = normalize(region.planes[k].normal);
    sides.side[sides.count++] = {n, dot(n, region.planes[k].point - origin)};
  }
  return sides;
}

std::optional<RegionEntry> entry_through(const RegionSides& sides, Vec3d eye, Vec3d d) {
  double t_in = 0, t_out = std::numeric_limits<double>::infinity();
  int entered = -1;
  for (int k = 0; k < sides.count; ++k) {
    const double toward = dot(sides.side[k].normal, d);
    const double room = sides.side[k].offset - dot(sides.side[k].normal, eye);  // < 0: outside
    if (toward == 0) {
      if (room < 0) return std::nullopt;  // parallel, outside: the ray never enters
      continue;
    }
    const double t = room / toward;
    if (toward > 0) {
      t_out = std::min(t_out, t);
    } else if (room < 0 && t > t_in) {
      t_in = t;
      entered = k;
    }
  }
  if (entered < 0 || t_in > t_out) return std::nullopt;
  return RegionEntry{t_in, sides.side[entered].normal};
}

// The cap hits of one image row, structure of arrays as render/scene/shade.hpp's RayHits reads
// them.
struct CapRow {
  std::vector<float> dx, dy, dz, nx, ny, nz, t, value;
  std::vector<float> light, depth;  // sized by draw_row, once the row's hits are known
  std::vector<int> column;
  std::vector<std::uint32_t> key;

  explicit CapRow(int width) {
    for (auto* v : {&dx, &dy, &dz, &nx, &ny, &nz, &t, &light, &depth, &value}) v->reserve(width);
    column.reserve(width);
    key.reserve(width);
  }
  RayHits hits() const {
    return {dx.data(), dy.data(), dz.data(), nx.data(),
            ny.data(), nz.data(), t.data(),  static_cast<int>(t.size())};
  }
};

double field_at(const TetVolume& volume, const ClipCap& cap, const PointLocation& at) {
  const Tet& tet = volume.tets[at.tet];
  double value = 0;
  for (int c = 0; c < 4; ++c) value += at.weight[c] * cap.field[tet.v[c]];
  return value;
}

struct CapFrame {
  const TetVolume& volume;
  const Bvh& bvh;
  const Camera& camera;
  const CameraFrame& view;
  const TraceOptions& options;
  const ClipCap& cap;
  Vec3d eye;  // local
  RegionSides sides;
  const FaceAdjacency<Tet20>* adjacency;  // null: no walking
};

// Collects the row's rays whose entry point into the region lies in one of this rank's tets.
// Neighbouring pixels' points mostly share a tet or lie a face or two apart: the last one found
// is tried first and walked from, which gives locate_point's answer whenever the walk ends with
// the point strictly inside a tet.
void find_cap_hits(const CapFrame& f, int j, CapRow& row) {
  std::optional<std::uint32_t> last;
  for (int i = 0; i < f.camera.width; ++i) {
    const Vec3d d = pixel_direction(f.view, f.camera, i, j);
    const std::optional<RegionEntry> entry = entry_through(f.sides, f.eye, d);
    if (!entry) continue;
    const Vec3d point = f.eye + entry->t * d;
    if (!within_bounds(f.bvh, point)) continue;  // on another rank, or outside the mesh
    std::optional<PointLocation> at;
    if (last) {
      at = f.adjacency != nullptr ? locate_by_walking(f.volume, *f.adjacency, *last, point)
                                  : locate_strictly_inside(f.volume, *last, point);
    }
    if (!at) at = locate_point(f.volume, f.bvh, point);
    if (!at) continue;
    last = at->tet;
    row.column.push_back(i);
    row.key.push_back(f.volume.tet_ids[at->tet]);
    row.value.push_back(static_cast<float>(field_at(f.volume, f.cap, *at)));
    row.dx.push_back(static_cast<float>(d.x));
    row.dy.push_back(static_cast<float>(d.y));
    row.dz.push_back(static_cast<float>(d.z));
    row.nx.push_back(static_cast<float>(entry->normal.x));
    row.ny.push_back(static_cast<float>(entry->normal.y));
    row.nz.push_back(static_cast<float>(entry->normal.z));
    row.t.push_back(static_cast<float>(entry->t));
  }
}

void cap_color(const ClipCap& cap, float value, float rgb[3]) {
  const float span = cap.range_hi - cap.range_lo;
  cap.colormap->lookup(span > 0 ? (value - cap.range_lo) / span : 0.5f, rgb);
}

void write_pixel(Framebuffer& image, std::size_t p, const float rgb[3], float light, float depth,
                 std::uint32_t key) {
  for (int k = 0; k < 3; ++k) image.rgba[4 * p + k] = rgb[k] * light;
  image.rgba[4 * p + 3] = 1.0f;
  image.depth[p] = depth;
  image.hit[p] = key;
}

// Puts the row's cap hits over the traced pixels they win against (the cap wins a tie with a
// hit of its own tet: the cut face lies in front of the surface inside it).
void draw_row(const CapFrame& f, const ShadeContext& shade, const LocalLights* lights, int j,
              CapRow& row, Framebuffer& image, std::vector<Framebuffer>* shadow_terms) {
  const RayHits hits = row.hits();
  if (hits.count == 0) return;
  row.light.resize(row.t.size());
  row.depth.resize(row.t.size());
  light_and_depth(shade, hits, row.light.data(), row.depth.data());
  std::vector<std::vector<float>> factor;
  if (lights) {
    factor.assign(kMaxLights, std::vector<float>(hits.count));
    float* factors[kMaxLights];
    for (int k = 0; k < kMaxLights; ++k) factors[k] = factor[k].data();
    light_terms(shade, *lights, hits, static_cast<Vec3f>(f.eye), row.light.data(), factors);
  }
  for (int r = 0; r < hits.count; ++r) {
    const std::size_t p = image.index(row.column[r], j);
    if (wins_over(image.depth[p], image.hit[p], row.depth[r], row.key[r])) continue;
    float rgb[3];
    cap_color(f.cap, row.value[r], rgb);
    write_pixel(image, p, rgb, row.light[r], row.depth[r], row.key[r]);
    if (!shadow_terms) continue;
    for (std::size_t k = 0; k < shadow_terms->size(); ++k)
      write_pixel((*shadow_terms)[k], p, rgb, factor[k][r], row.depth[r], row.key[r]);
  }
}

}  // namespace

std::optional<RegionEntry> enter_region(const ClipRegion& region, Vec3d origin, Vec3d eye,
                                        Vec3d d) {
  return entry_through(region_sides(region, origin), eye, d);
}

void draw_clip_cap(Framebuffer& image, const TetVolume& volume, const Bvh& bvh,
                   const Camera& camera, const TraceOptions& options, const ClipCap& cap,
                   std::vector<Framebuffer>* shadow_terms, const FaceAdjacency<Tet20>* adjacency) {
  if (cap.colormap == nullptr || options.clip.empty() || bvh.empty()) return;
  const CameraFrame view = make_frame(camera);
  const CapFrame f{volume,
                   bvh,
                   camera,
                   view,
                   options,
                   cap,
                   view.eye - volume.origin,
                   region_sides(options.clip, volume.origin),
                   adjacency};
  const ShadeContext shade{volume, view, {}, nullptr, options};
  const LocalLights lights = local_lights(options.lights, volume.origin);
  const LocalLights* lit = options.lights.headlight_only() ? nullptr : &lights;
  tbb::parallel_for(0, camera.height, [&](int j) {
    CapRow row(camera.width);
    find_cap_hits(f, j, row);
    draw_row(f, shade, lit, j, row, image, shadow_terms);
  });
}

}  // namespace tetray::render
