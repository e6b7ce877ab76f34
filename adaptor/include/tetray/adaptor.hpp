// tetray's public C++ API: the only door for a solver. Modeled on the Catalyst/Ascent
// initialize/execute/finalize cycle, but zero-copy: every view below is non-owning and is only
// read during the call that receives it. No exception crosses this API; every call returns a
// Status, and the solver decides what to do with it.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tetray {

enum class StatusCode {
  ok = 0,
  invalid_argument,  // bad views: sizes, indices out of range, NaN/Inf under policy "error"
  config_error,      // the YAML config: file, line and key in the message
  io_error,          // output directory or image file could not be written
  mpi_error,
  internal_error,
  not_initialized,
  // The call completed, but some scenes were skipped (a field missing or unusable on some rank);
  // the message names each skipped scene and why. The other scenes rendered.
  partial,
};

// Every collective call (create, execute, finalize) returns the same code on every rank of the
// adaptor's communicator; a message caused by one rank starts with "rank N: ".
struct Status {
  StatusCode code = StatusCode::ok;
  std::string message;

  bool ok() const { return code == StatusCode::ok; }
  // Neither ok nor partial: the call did nothing a solver can rely on (no scene rendered).
  bool failed() const { return code != StatusCode::ok && code != StatusCode::partial; }
  static Status success() { return {}; }
};

enum class ScalarType : std::uint8_t { float32, float64 };
enum class IndexType : std::uint8_t { int32, int64 };

// Point coordinates, xyz interleaved, float or double; optionally a displacement of the same
// layout that is added to them (reference coordinates + displacement = current position).
struct PointsView {
  const void* xyz = nullptr;
  ScalarType type = ScalarType::float64;
  std::size_t count = 0;               // number of points
  const void* displacement = nullptr;  // optional, same count
  ScalarType displacement_type = ScalarType::float64;

  static PointsView of(std::span<const double> xyz) {
    return {xyz.data(), ScalarType::float64, xyz.size() / 3};
  }
  static PointsView of(std::span<const float> xyz) {
    return {xyz.data(), ScalarType::float32, xyz.size() / 3};
  }
};

// Tet connectivity, 4 point indices per tet, int32 or int64.
struct TetsView {
  const void* connectivity = nullptr;
  IndexType type = IndexType::int64;
  std::size_t count = 0;  // number of tets
  // Optional per-tet VTK vtkGhostType flags: tets with DUPLICATECELL (1) or HIDDENCELL (32)
  // are not rendered.
  const std::uint8_t* ghost = nullptr;
  // Optional global tet ids (unique across ranks, below 2^32-1): the fastest way to make exact
  // depth ties resolve alike for any rank count. Without them tetray derives each tet's key from
  // its corners' coordinates (the reference coordinates at the last topology change), which
  // every partition computes alike too.
  const std::int64_t* global_ids = nullptr;

  static TetsView of(std::span<const std::int64_t> c) {
    return {c.data(), IndexType::int64, c.size() / 4};
  }
  static TetsView of(std::span<const std::int32_t> c) {
    return {c.data(), IndexType::int32, c.size() / 4};
  }
};

// Cells of the types finite-element solvers write, laid out as VTK stores them: cell c has the
// VTK type types[c] and the point indices connectivity[offsets[c], offsets[c + 1]) in VTK's node
// order. Accepted: VTK_TETRA (10), VTK_HEXAHEDRON (12), VTK_WEDGE (13), VTK_PYRAMID (14),
// VTK_QUADRATIC_TETRA (24), and VTK_LAGRANGE_TETRAHEDRON (71) and VTK_LAGRANGE_HEXAHEDRON (72)
// of order 1 or 2. tetray splits them into tets at each topology change, through the mid-edge
// nodes of quadratic cells; a face two cells share is split alike on every rank (by the points'
// reference coordinates), so no crack opens between partitions. Depth ties resolve by the tets'
// corner positions (TetsView::global_ids has no counterpart here).
struct CellsView {
  const std::uint8_t* types = nullptr;
  const void* offsets = nullptr;        // count + 1 entries, offsets[0] = 0
  const void* connectivity = nullptr;   // offsets[count] entries
  IndexType type = IndexType::int64;    // of offsets and connectivity
  std::size_t count = 0;                // number of cells
  const std::uint8_t* ghost = nullptr;  // optional per-cell vtkGhostType flags, as TetsView's
};

// Points with either tets or cells (the other left empty).
struct MeshView {
  PointsView points;
  TetsView tets;
  CellsView cells{};  // "{}": MeshView{points, tets} compiles without -Wextra warnings
};

// One point field by name, one value per point.
struct FieldView {
  std::string_view name;
  const void* values = nullptr;
  ScalarType type = ScalarType::float64;
  std::size_t count = 0;

  static FieldView of(std::string_view name, std::span<const double> v) {
    return {name, v.data(), ScalarType::float64, v.size()};
  }
  static FieldView of(std::string_view name, std::span<const float> v) {
    return {name, v.data(), ScalarType::float32, v.size()};
  }
};

// What changed since the last execute call. The first call is always treated as a full change.
struct Changes {
  bool geometry = true;  // point coordinates or displacement
  bool topology = true;  // connectivity, tet count, ghost flags
  bool fields = true;    // field values
};

// What one execute call did (for the solver's own logging).
struct ExecuteReport {
  bool rendered = false;  // false on an off-trigger step
  int scenes_rendered = 0;
  double seconds_blocked = 0;               // time execute held the solver
  std::string bvh_decision;                 // "none", "field_refit", "refit", "rebuild"
  std::uint64_t tets_skipped = 0;           // under the skip_tets NaN/Inf policy
  std::vector<std::string> skipped_scenes;  // due but not rendered (status partial), by name
};

class Adaptor {
 public:
  // Reads and validates the whole config at once. `comm` is duplicated; the adaptor never uses
  // MPI_COMM_WORLD behind the caller's back. On error returns null and fills `status`.
  static std::unique_ptr<Adaptor> create(MPI_Comm comm, const std::string& config_path,
                                         Status& status);
  static std::unique_ptr<Adaptor> create_from_yaml(MPI_Comm comm, std::string_view yaml,
                                                   Status& status);
  ~Adaptor();
  Adaptor(const Adaptor&) = delete;
  Adaptor& operator=(const Adaptor&) = delete;

  // One solver step. Collective over the adaptor's communicator. Off-trigger steps return ok at
  // once, without MPI. An error the writer thread met since the last render step is returned by
  // the next render step (which then renders nothing) or by finalize, on every rank.
  Status execute(std::int64_t step, double time, const MeshView& mesh,
                 std::span<const FieldView> fields, const Changes& changes = {},
                 ExecuteReport* report = nullptr);

  // For a rank that could not prepare its views for this step (converting them failed, say):
  // called instead of execute, collectively like it, so that no other rank is left waiting in
  // the step. On a render step every rank returns `error`, prefixed with this rank's number; on
  // an off-trigger step ok, and `error` is returned by the next render step or finalize.
  Status execute_failed(std::int64_t step, double time, Status error, const Changes& changes = {},
                        ExecuteReport* report = nullptr);

  // Whether execute(step, time, ...) would render at least one scene. No side effects, no MPI:
  // lets a solver (or the VTK bridge) skip preparing views on off-trigger steps.
  bool will_render(std::int64_t step, double time) const;

  // Drains the writer queue, closes the logs and returns the writer's error, if any, on every
  // rank. Collective. Idempotent.
  Status finalize();

 private:
  class Impl;
  explicit Adaptor(std::unique_ptr<Impl> impl);
  // create and create_from_yaml with the config parser each uses (defined in adaptor.cpp).
  template <typename Parse>
  static std::unique_ptr<Adaptor> create_with(MPI_Comm comm, Parse&& parse, Status& status);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tetray
