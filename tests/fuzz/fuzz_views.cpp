// execute's view validation on arbitrary views: an adaptor created once (one per NaN policy)
// gets meshes and fields whose counts, indices, types, values (NaN, Inf, huge), ghost flags,
// global ids and displacement come from the fuzz input. Every buffer really holds the count its
// view declares (the API's contract); everything else may be wrong. Each call must return a
// status (ok or a message), never crash.
#include <fuzzer/FuzzedDataProvider.h>
#include <mpi.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tetray/adaptor.hpp"

namespace {

// Images and logs of every run go here; removed at exit, after the adaptors (constructed later)
// are destroyed.
struct OutputRoot {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("tetray_fuzz_views_" + std::to_string(::getpid()));
  ~OutputRoot() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

const std::filesystem::path& output_root() {
  static const OutputRoot root;
  return root.path;
}

std::unique_ptr<tetray::Adaptor> make_adaptor(const std::string& nonfinite) {
  const auto dir = output_root() / nonfinite;
  const std::string yaml = "output: {directory: " + dir.string() +
                           ", formats: [png], cinema: false, writer_queue_depth: 0, quiet: true}\n"
                           "nonfinite: " +
                           nonfinite +
                           "\n"
                           "scenes:\n"
                           "  - {name: iso, field: f, isovalues: [0.5], image: {width: 8, height: "
                           "8}}\n"
                           "  - {name: colored, field: f, isovalues: [0.25], color_by: g,\n"
                           "     image: {width: 8, height: 6},\n"
                           "     camera: {eye: [2, 1, 3], look_at: [0, 0, 0], up: [0, 1, 0]}}\n";
  tetray::Status status;
  auto adaptor = tetray::Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status);
  if (!adaptor) std::abort();
  return adaptor;
}

struct Adaptors {
  std::unique_ptr<tetray::Adaptor> error, skip;
};

Adaptors& adaptors() {
  static Adaptors a = [] {
    output_root();
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) MPI_Init(nullptr, nullptr);
    return Adaptors{make_adaptor("error"), make_adaptor("skip_tets")};
  }();
  return a;
}

double pick_value(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 7)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return std::numeric_limits<double>::infinity();
    case 2:
      return -std::numeric_limits<double>::infinity();
    case 3:
      return std::numeric_limits<double>::max();
    case 4:
      return in.ConsumeFloatingPoint<double>();
    default:
      return in.ConsumeFloatingPointInRange<double>(-2, 2);
  }
}

// A scalar array of `count` values in float or double; `type` says which one was filled.
struct Scalars {
  tetray::ScalarType type = tetray::ScalarType::float64;
  std::vector<double> doubles;
  std::vector<float> floats;
  const void* data() const {
    return type == tetray::ScalarType::float64 ? static_cast<const void*>(doubles.data())
                                               : static_cast<const void*>(floats.data());
  }
};

Scalars scalars(FuzzedDataProvider& in, std::size_t count) {
  Scalars s;
  s.type = in.ConsumeBool() ? tetray::ScalarType::float64 : tetray::ScalarType::float32;
  for (std::size_t i = 0; i < count; ++i) {
    const double v = pick_value(in);
    if (s.type == tetray::ScalarType::float64) {
      s.doubles.push_back(v);
    } else {
      s.floats.push_back(static_cast<float>(v));
    }
  }
  return s;
}

struct Connectivity {
  tetray::IndexType type = tetray::IndexType::int64;
  std::vector<std::int64_t> wide;
  std::vector<std::int32_t> narrow;
  const void* data() const {
    return type == tetray::IndexType::int64 ? static_cast<const void*>(wide.data())
                                            : static_cast<const void*>(narrow.data());
  }
};

// Mostly valid indices into `points`, sometimes anything.
Connectivity connectivity(FuzzedDataProvider& in, std::size_t tets, std::size_t points) {
  Connectivity c;
  c.type = in.ConsumeBool() ? tetray::IndexType::int64 : tetray::IndexType::int32;
  const auto top = static_cast<std::int64_t>(points);
  for (std::size_t i = 0; i < 4 * tets; ++i) {
    const std::int64_t v = in.ConsumeIntegralInRange(0, 9) == 0
                               ? in.ConsumeIntegral<std::int64_t>()
                               : in.ConsumeIntegralInRange<std::int64_t>(0, top);
    if (c.type == tetray::IndexType::int64) {
      c.wide.push_back(v);
    } else {
      c.narrow.push_back(static_cast<std::int32_t>(v));
    }
  }
  return c;
}

std::size_t count_near(FuzzedDataProvider& in, std::size_t n) {
  return in.ConsumeIntegralInRange(0, 5) == 0 ? in.ConsumeIntegralInRange<std::size_t>(0, 64) : n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static std::int64_t step = 0;
  FuzzedDataProvider in(data, size);
  tetray::Adaptor& adaptor = in.ConsumeBool() ? *adaptors().error : *adaptors().skip;
  const std::size_t points = in.ConsumeIntegralInRange<std::size_t>(0, 40);
  const std::size_t tets = in.ConsumeIntegralInRange<std::size_t>(0, 40);
  const Scalars xyz = scalars(in, 3 * points);
  const Connectivity cells = connectivity(in, tets, points);
  const bool with_displacement = in.ConsumeBool();
  const Scalars displacement = scalars(in, with_displacement ? 3 * points : 0);
  std::vector<std::uint8_t> ghost;
  if (in.ConsumeBool()) {
    for (std::size_t t = 0; t < tets; ++t) ghost.push_back(in.ConsumeIntegral<std::uint8_t>());
  }
  std::vector<std::int64_t> global_ids;
  if (in.ConsumeBool()) {
    for (std::size_t t = 0; t < tets; ++t) global_ids.push_back(in.ConsumeIntegral<std::int64_t>());
  }
  tetray::MeshView mesh;
  mesh.points = {xyz.data(), xyz.type, points, with_displacement ? displacement.data() : nullptr,
                 displacement.type};
  mesh.tets = {cells.data(), cells.type, tets, ghost.empty() ? nullptr : ghost.data(),
               global_ids.empty() ? nullptr : global_ids.data()};
  const std::size_t f_count = count_near(in, points);
  const std::size_t g_count = count_near(in, points);
  const Scalars f = scalars(in, f_count);
  const Scalars g = scalars(in, g_count);
  std::vector<tetray::FieldView> fields;
  if (in.ConsumeIntegralInRange(0, 7) != 0) fields.push_back({"f", f.data(), f.type, f_count});
  if (in.ConsumeIntegralInRange(0, 7) != 0) fields.push_back({"g", g.data(), g.type, g_count});
  const double time = in.ConsumeBool() ? pick_value(in) : static_cast<double>(step);
  tetray::ExecuteReport report;
  // Every array is new, so everything changed (Changes{} says so): the flags are the caller's
  // promise, not input to validate.
  const tetray::Status status = adaptor.execute(step++, time, mesh, fields, {}, &report);
  if (!status.ok() && status.message.empty()) std::abort();
  return 0;
}
