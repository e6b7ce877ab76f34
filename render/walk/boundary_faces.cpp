#include "render/walk/boundary_faces.hpp"

#include <algorithm>
#include <limits>

#include "render/walk/slab_ray.hpp"

namespace tetray::render {
namespace {

constexpr std::uint32_t kLeafFaces = 4;

Vec3d face_center(const TetVolume& volume, const BoundaryFace& face) {
  Vec3d c{};
  for (std::uint32_t v : face.vertex) c = c + vertex_position(volume, v);
  return (1.0 / 3.0) * c;
}

// Splits faces [first, last) at the median of the longest axis of their centers, children of
// `node` at the end of `nodes`.
void split(const TetVolume& volume, std::vector<BoundaryFace>& faces,
           std::vector<BoundaryNode>& nodes, std::uint32_t node, std::uint32_t first,
           std::uint32_t last) {
  if (last - first <= kLeafFaces) {
    nodes[node].first = first;
    nodes[node].count = last - first;
    return;
  }
  Vec3d lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()};
  Vec3d hi = -lo;
  for (std::uint32_t f = first; f < last; ++f) {
    const Vec3d c = face_center(volume, faces[f]);
    lo = min(lo, c);
    hi = max(hi, c);
  }
  const Vec3d extent = hi - lo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t middle = first + (last - first) / 2;
  std::nth_element(faces.begin() + first, faces.begin() + middle, faces.begin() + last,
                   [&](const BoundaryFace& a, const BoundaryFace& b) {
                     const double ca = face_center(volume, a)[axis];
                     const double cb = face_center(volume, b)[axis];
                     return ca < cb || (ca == cb && a.tet < b.tet) ||
                            (ca == cb && a.tet == b.tet && a.opposite_vertex < b.opposite_vertex);
                   });
  const auto children = static_cast<std::uint32_t>(nodes.size());
  nodes.resize(nodes.size() + 2);
  nodes[node].first = children;
  nodes[node].count = 0;
  split(volume, faces, nodes, children, first, middle);
  split(volume, faces, nodes, children + 1, middle, last);
}

// The face projected and ordered counter-clockwise around the ray, when the ray passes
// through it into the domain.
std::optional<ProjectedFace> entering(const TetVolume& volume, const RayFrame& frame,
                                      const BoundaryFace& face) {
  ProjectedFace p{};
  for (int c = 0; c < 3; ++c) {
    p.vertex[c] = face.vertex[c];
    p.point[c] = frame.project(vertex_position(volume, face.vertex[c]));
  }
  const int s01 = ray_side(p.point[0], p.vertex[0], p.point[1], p.vertex[1]);
  const int s12 = ray_side(p.point[1], p.vertex[1], p.point[2], p.vertex[2]);
  const int s20 = ray_side(p.point[2], p.vertex[2], p.point[0], p.vertex[0]);
  if (s01 != s12 || s12 != s20) return std::nullopt;
  if (s01 < 0) {
    std::swap(p.vertex[1], p.vertex[2]);
    std::swap(p.point[1], p.point[2]);
  }
  // Counter-clockwise around the ray means the face's normal (b - a) x (c - a) points along
  // the ray: it enters when the tet lies on that side.
  const Vec3d a = vertex_position(volume, p.vertex[0]);
  const Vec3d n =
      cross(vertex_position(volume, p.vertex[1]) - a, vertex_position(volume, p.vertex[2]) - a);
  if (!(dot(n, vertex_position(volume, face.opposite_vertex) - a) > 0)) return std::nullopt;
  return p;
}

bool is_after(double t, std::uint32_t face, const EntryCursor& cursor) {
  return !cursor.any || t > cursor.t || (t == cursor.t && face > cursor.face);
}

}  // namespace

std::optional<FaceEntry> entry_behind(const TetVolume& volume, const RayFrame& frame,
                                      std::uint32_t tet, std::span<const float> second) {
  const Tet& t = volume.tets[tet];
  // The ray's line enters a tet through exactly one face (ray_side decides every tie).
  for (int k = 0; k < 4; ++k) {
    BoundaryFace face{};
    for (int c = 0; c < 3; ++c) face.vertex[c] = static_cast<std::uint32_t>(t.v[(k + 1 + c) % 4]);
    face.opposite_vertex = static_cast<std::uint32_t>(t.v[k]);
    face.tet = tet;
    if (const std::optional<ProjectedFace> projected = entering(volume, frame, face)) {
      return FaceEntry{kBoundaryFace, tet, *projected,
                       cross_face(volume, frame, *projected, second)};
    }
  }
  return std::nullopt;
}

BoundaryFaces build_boundary_faces(const TetVolume& volume,
                                   std::span<const BoundaryFaceRef> boundary) {
  BoundaryFaces result;
  result.faces.reserve(boundary.size());
  for (const BoundaryFaceRef& ref : boundary) {
    const Tet& tet = volume.tets[ref.tet];
    BoundaryFace face{};
    int n = 0;
    for (std::uint32_t c = 0; c < 4; ++c) {
      if (c != ref.opposite) face.vertex[n++] = static_cast<std::uint32_t>(tet.v[c]);
    }
    face.opposite_vertex = static_cast<std::uint32_t>(tet.v[ref.opposite]);
    face.tet = ref.tet;
    result.faces.push_back(face);
  }
  if (result.faces.empty()) return result;
  result.nodes.resize(1);
  split(volume, result.faces, result.nodes, 0, 0, static_cast<std::uint32_t>(result.faces.size()));
  refit_boundary_faces(volume, result);
  return result;
}

void refit_boundary_faces(const TetVolume& volume, BoundaryFaces& boundary) {
  for (std::size_t i = boundary.nodes.size(); i-- > 0;) {
    BoundaryNode& node = boundary.nodes[i];
    std::fill(node.lo, node.lo + 3, std::numeric_limits<float>::infinity());
    std::fill(node.hi, node.hi + 3, -std::numeric_limits<float>::infinity());
    const auto grow = [&](const float* lo, const float* hi) {
      for (int a = 0; a < 3; ++a) {
        node.lo[a] = std::min(node.lo[a], lo[a]);
        node.hi[a] = std::max(node.hi[a], hi[a]);
      }
    };
    if (node.count == 0) {
      for (std::uint32_t c = node.first; c < node.first + 2; ++c) {
        grow(boundary.nodes[c].lo, boundary.nodes[c].hi);
      }
      continue;
    }
    for (std::uint32_t f = node.first; f < node.first + node.count; ++f) {
      for (std::uint32_t v : boundary.faces[f].vertex) {
        const Vertex& p = volume.vertices[v];
        const float xyz[3] = {p.x, p.y, p.z};
        grow(xyz, xyz);
      }
    }
  }
  // Children before parents above, so every parent grew from its children's exact bounds.
  for (BoundaryNode& node : boundary.nodes) grow_box(node.lo, node.hi);
}

std::optional<FaceEntry> next_entry(const TetVolume& volume, const BoundaryFaces& boundary,
                                    const RayFrame& frame, double t_from, EntryCursor after,
                                    std::span<const float> second,
                                    const EntryCandidates* candidates) {
  if (boundary.nodes.empty()) return std::nullopt;
  std::optional<FaceEntry> best;
  double t_best = std::numeric_limits<double>::infinity();
  // The best entry in (t, face) order is the same whichever order the faces are tried in.
  const auto consider = [&](std::uint32_t f) {
    const std::optional<ProjectedFace> projected = entering(volume, frame, boundary.faces[f]);
    if (!projected) return;
    const FaceCrossing crossing = cross_face(volume, frame, *projected, second);
    if (crossing.t < t_from || !is_after(crossing.t, f, after)) return;
    if (best && (crossing.t > t_best || (crossing.t == t_best && f > best->face))) return;
    best = FaceEntry{f, boundary.faces[f].tet, *projected, crossing};
    t_best = crossing.t;
  };
  if (candidates != nullptr) {
    for (const std::uint32_t f : candidates->tile) consider(f);
    for (const std::uint32_t f : candidates->everywhere) consider(f);
    return best;
  }
  const SlabRay ray(frame);
  visit_nearest_first<64>(
      t_best,
      [&](std::uint32_t i) {
        return slab_entry(ray, boundary.nodes[i].lo, boundary.nodes[i].hi, t_from, t_best);
      },
      [&](std::uint32_t i) { return boundary.nodes[i].count != 0; },
      [&](std::uint32_t i) { return boundary.nodes[i].first; },
      [&](std::uint32_t i) {
        const BoundaryNode& node = boundary.nodes[i];
        for (std::uint32_t f = node.first; f < node.first + node.count; ++f) consider(f);
      });
  return best;
}

}  // namespace tetray::render
