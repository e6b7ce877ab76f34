// The C API of tetray/adaptor.h over the C++ Adaptor: a handle holds the views set by the
// solver, and every call catches what the C++ side could throw.
#include "tetray/adaptor.h"

#include <memory>
#include <string>
#include <vector>

#include "tetray/adaptor.hpp"

struct tetray_adaptor {
  std::unique_ptr<tetray::Adaptor> adaptor;
  tetray::MeshView mesh;
  std::vector<std::string> field_names;  // owned names; views point into them
  std::vector<tetray::FieldView> fields;
  tetray::ExecuteReport report;
};

namespace {

// The message of this thread's last call: every call sets it, so an old one never outlives a
// later success.
thread_local std::string last_error;

int fail(tetray::StatusCode code, std::string message) {
  last_error = std::move(message);
  return static_cast<int>(code);
}

int succeed() {
  last_error.clear();
  return TETRAY_OK;
}

int finish(const tetray::Status& status) {
  if (status.ok()) return succeed();
  return fail(status.code, status.message);
}

bool valid_scalar(int type) { return type == TETRAY_FLOAT32 || type == TETRAY_FLOAT64; }

tetray::ScalarType scalar(int type) {
  return type == TETRAY_FLOAT32 ? tetray::ScalarType::float32 : tetray::ScalarType::float64;
}

bool valid_index(int type) { return type == TETRAY_INT32 || type == TETRAY_INT64; }

tetray::IndexType index(int type) {
  return type == TETRAY_INT32 ? tetray::IndexType::int32 : tetray::IndexType::int64;
}

template <typename Make>
int create(Make&& make, tetray_adaptor** out) {
  if (out == nullptr) return fail(tetray::StatusCode::invalid_argument, "create: out is NULL");
  *out = nullptr;
  try {
    tetray::Status status;
    auto adaptor = make(status);
    if (!adaptor) return finish(status);
    *out = new tetray_adaptor{std::move(adaptor), {}, {}, {}, {}};
    return succeed();
  } catch (const std::exception& e) {
    return fail(tetray::StatusCode::internal_error, std::string("create: ") + e.what());
  }
}

int create_from_path(MPI_Comm comm, const char* path, tetray_adaptor** out) {
  if (path == nullptr)
    return fail(tetray::StatusCode::invalid_argument, "create: config_path is NULL");
  return create([&](tetray::Status& s) { return tetray::Adaptor::create(comm, path, s); }, out);
}

int create_from_text(MPI_Comm comm, const char* yaml, tetray_adaptor** out) {
  if (yaml == nullptr) return fail(tetray::StatusCode::invalid_argument, "create: yaml is NULL");
  return create([&](tetray::Status& s) { return tetray::Adaptor::create_from_yaml(comm, yaml, s); },
                out);
}

int no_handle(const char* call) {
  return fail(tetray::StatusCode::not_initialized, std::string(call) + ": the handle is NULL");
}

}  // namespace

extern "C" {

int tetray_create(MPI_Comm comm, const char* config_path, tetray_adaptor** out) {
  return create_from_path(comm, config_path, out);
}

int tetray_create_from_yaml(MPI_Comm comm, const char* yaml, tetray_adaptor** out) {
  return create_from_text(comm, yaml, out);
}

int tetray_create_f(MPI_Fint comm, const char* config_path, tetray_adaptor** out) {
  return create_from_path(MPI_Comm_f2c(comm), config_path, out);
}

int tetray_create_from_yaml_f(MPI_Fint comm, const char* yaml, tetray_adaptor** out) {
  return create_from_text(MPI_Comm_f2c(comm), yaml, out);
}

int tetray_set_mesh(tetray_adaptor* a, const void* xyz, int xyz_type, int64_t point_count,
                    const void* displacement, int displacement_type, const void* connectivity,
                    int index_type, int64_t tet_count, const uint8_t* ghost,
                    const int64_t* global_ids) {
  if (a == nullptr) return no_handle("tetray_set_mesh");
  if (!valid_scalar(xyz_type) || !valid_scalar(displacement_type)) {
    return fail(tetray::StatusCode::invalid_argument,
                "tetray_set_mesh: scalar types must be TETRAY_FLOAT32 or TETRAY_FLOAT64");
  }
  if (!valid_index(index_type)) {
    return fail(tetray::StatusCode::invalid_argument,
                "tetray_set_mesh: index_type must be TETRAY_INT32 or TETRAY_INT64");
  }
  if (point_count < 0 || tet_count < 0) {
    return fail(tetray::StatusCode::invalid_argument, "tetray_set_mesh: negative count");
  }
  a->mesh.points = {xyz, scalar(xyz_type), static_cast<std::size_t>(point_count), displacement,
                    scalar(displacement_type)};
  a->mesh.tets = {connectivity, index(index_type), static_cast<std::size_t>(tet_count), ghost,
                  global_ids};
  a->mesh.cells = {};
  return succeed();
}

int tetray_set_cells(tetray_adaptor* a, const uint8_t* types, const void* offsets,
                     const void* connectivity, int index_type, int64_t cell_count,
                     const uint8_t* ghost) {
  if (a == nullptr) return no_handle("tetray_set_cells");
  if (!valid_index(index_type)) {
    return fail(tetray::StatusCode::invalid_argument,
                "tetray_set_cells: index_type must be TETRAY_INT32 or TETRAY_INT64");
  }
  if (cell_count < 0) {
    return fail(tetray::StatusCode::invalid_argument, "tetray_set_cells: negative count");
  }
  a->mesh.tets = {};
  a->mesh.cells = {
      types, offsets, connectivity, index(index_type), static_cast<std::size_t>(cell_count), ghost};
  return succeed();
}

int tetray_set_field(tetray_adaptor* a, const char* name, const void* values, int type,
                     int64_t count) {
  if (a == nullptr) return no_handle("tetray_set_field");
  if (name == nullptr || *name == '\0' || !valid_scalar(type) || count < 0) {
    return fail(tetray::StatusCode::invalid_argument,
                "tetray_set_field: needs a non-empty name, TETRAY_FLOAT32/64 and count >= 0");
  }
  try {
    std::size_t k = 0;
    while (k < a->field_names.size() && a->field_names[k] != name) ++k;
    if (k == a->field_names.size()) {
      a->field_names.emplace_back(name);
      a->fields.emplace_back();
      // Growing may move the strings: re-point every view at its name.
      for (std::size_t i = 0; i < a->fields.size(); ++i) a->fields[i].name = a->field_names[i];
    }
    a->fields[k] = {a->field_names[k], values, scalar(type), static_cast<std::size_t>(count)};
    return succeed();
  } catch (const std::exception& e) {
    return fail(tetray::StatusCode::internal_error, std::string("tetray_set_field: ") + e.what());
  }
}

int tetray_clear_fields(tetray_adaptor* a) {
  if (a == nullptr) return no_handle("tetray_clear_fields");
  a->fields.clear();
  a->field_names.clear();
  return succeed();
}

int tetray_will_render(const tetray_adaptor* a, int64_t step, double time, int* will_render) {
  if (a == nullptr) return no_handle("tetray_will_render");
  if (will_render == nullptr) {
    return fail(tetray::StatusCode::invalid_argument, "tetray_will_render: will_render is NULL");
  }
  *will_render = a->adaptor->will_render(step, time) ? 1 : 0;
  return succeed();
}

int tetray_execute(tetray_adaptor* a, int64_t step, double time, int changes) {
  if (a == nullptr) return no_handle("tetray_execute");
  const tetray::Changes flags{(changes & TETRAY_CHANGED_GEOMETRY) != 0,
                              (changes & TETRAY_CHANGED_TOPOLOGY) != 0,
                              (changes & TETRAY_CHANGED_FIELDS) != 0};
  return finish(a->adaptor->execute(step, time, a->mesh, a->fields, flags, &a->report));
}

int tetray_get_report(const tetray_adaptor* a, tetray_report* report) {
  if (a == nullptr) return no_handle("tetray_get_report");
  if (report == nullptr)
    return fail(tetray::StatusCode::invalid_argument, "tetray_get_report: report is NULL");
  report->rendered = a->report.rendered ? 1 : 0;
  report->scenes_rendered = a->report.scenes_rendered;
  report->seconds_blocked = a->report.seconds_blocked;
  report->tets_skipped = a->report.tets_skipped;
  report->scenes_skipped = static_cast<int>(a->report.skipped_scenes.size());
  report->bvh_decision = a->report.bvh_decision.c_str();
  return succeed();
}

int tetray_get_skipped_scene(const tetray_adaptor* a, int index, const char** name) {
  if (a == nullptr) return no_handle("tetray_get_skipped_scene");
  const auto& skipped = a->report.skipped_scenes;
  if (name == nullptr || index < 0 || static_cast<std::size_t>(index) >= skipped.size()) {
    return fail(tetray::StatusCode::invalid_argument,
                "tetray_get_skipped_scene: needs a name pointer and 0 <= index < " +
                    std::to_string(skipped.size()));
  }
  *name = skipped[static_cast<std::size_t>(index)].c_str();
  return succeed();
}

int tetray_finalize(tetray_adaptor* a) {
  if (a == nullptr) return no_handle("tetray_finalize");
  return finish(a->adaptor->finalize());
}

void tetray_destroy(tetray_adaptor* a) { delete a; }

const char* tetray_last_error(void) { return last_error.c_str(); }

}  // extern "C"
