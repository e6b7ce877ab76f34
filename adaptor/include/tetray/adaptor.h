/* tetray's C API: the same calls as tetray/adaptor.hpp for C and, through ISO_C_BINDING, for
 * Fortran (module tetray, adaptor/fortran/tetray.f90). A handle keeps non-owning views of the
 * solver's arrays, set with tetray_set_mesh and tetray_set_field; they must stay valid until
 * the tetray_execute call that reads them. Every call returns a tetray_status, and
 * tetray_last_error() is the message of the last call on this thread: "" after a call that
 * returned TETRAY_OK (it does not keep an older error). Nothing aborts or throws. Collective
 * calls return the same status on every rank of the adaptor's communicator; a message caused by
 * one rank starts with "rank N: ". */
#ifndef TETRAY_ADAPTOR_H
#define TETRAY_ADAPTOR_H

#include <mpi.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tetray_adaptor tetray_adaptor;

/* Same values as tetray::StatusCode. */
typedef enum {
  TETRAY_OK = 0,
  TETRAY_INVALID_ARGUMENT = 1,
  TETRAY_CONFIG_ERROR = 2,
  TETRAY_IO_ERROR = 3,
  TETRAY_MPI_ERROR = 4,
  TETRAY_INTERNAL_ERROR = 5,
  TETRAY_NOT_INITIALIZED = 6,
  /* The call completed but skipped some scenes (a field missing or unusable on some rank): the
   * message names each scene and why; tetray_get_skipped_scene lists them. */
  TETRAY_PARTIAL = 7
} tetray_status;

enum { TETRAY_FLOAT32 = 0, TETRAY_FLOAT64 = 1 }; /* scalar types */
enum { TETRAY_INT32 = 0, TETRAY_INT64 = 1 };     /* index types */
/* What changed since the last tetray_execute: a bitwise or of these. */
enum {
  TETRAY_CHANGED_GEOMETRY = 1,
  TETRAY_CHANGED_TOPOLOGY = 2,
  TETRAY_CHANGED_FIELDS = 4,
  TETRAY_CHANGED_ALL = 7
};

/* What the last tetray_execute did. bvh_decision ("none", "field_refit", "refit", "rebuild")
 * stays valid until the next tetray_execute on the handle. */
typedef struct {
  int rendered;
  int scenes_rendered;
  double seconds_blocked;
  uint64_t tets_skipped;
  int scenes_skipped; /* due but skipped: the call returned TETRAY_PARTIAL */
  const char* bvh_decision;
} tetray_report;

/* Collective. On success *out is a new handle; on failure *out is NULL. */
int tetray_create(MPI_Comm comm, const char* config_path, tetray_adaptor** out);
int tetray_create_from_yaml(MPI_Comm comm, const char* yaml, tetray_adaptor** out);
/* The same for a Fortran communicator handle (MPI_Comm_c2f / mpi_f08 %MPI_VAL). */
int tetray_create_f(MPI_Fint comm, const char* config_path, tetray_adaptor** out);
int tetray_create_from_yaml_f(MPI_Fint comm, const char* yaml, tetray_adaptor** out);

/* Points: xyz interleaved (count points); displacement may be NULL. Tets: 4 indices each,
 * 0-based; ghost (vtkGhostType per tet) and global_ids may be NULL. */
int tetray_set_mesh(tetray_adaptor* a, const void* xyz, int xyz_type, int64_t point_count,
                    const void* displacement, int displacement_type, const void* connectivity,
                    int index_type, int64_t tet_count, const uint8_t* ghost,
                    const int64_t* global_ids);
/* Cells instead of tets, after tetray_set_mesh (which clears them; pass it no tets): cell c has
 * the VTK type types[c] and the 0-based point indices connectivity[offsets[c] .. offsets[c+1])
 * in VTK's node order (cell_count + 1 offsets, int32 or int64 like the connectivity). Accepted:
 * VTK types 10, 12, 13, 14, 24, and 71 and 72 of order 1 or 2, split into tets at each topology
 * change (see tetray::CellsView). ghost (vtkGhostType per cell) may be NULL. */
int tetray_set_cells(tetray_adaptor* a, const uint8_t* types, const void* offsets,
                     const void* connectivity, int index_type, int64_t cell_count,
                     const uint8_t* ghost);
/* Adds the point field `name` or replaces its view. */
int tetray_set_field(tetray_adaptor* a, const char* name, const void* values, int type,
                     int64_t count);
int tetray_clear_fields(tetray_adaptor* a);

/* Sets *will_render to 1 when tetray_execute(step, time) would render at least one scene, else
 * 0. No MPI, no side effects: lets a solver skip preparing its fields on off-trigger steps. */
int tetray_will_render(const tetray_adaptor* a, int64_t step, double time, int* will_render);

/* Collective. `changes`: TETRAY_CHANGED_* bits. Off-trigger steps return TETRAY_OK at once,
 * without MPI; a writer error is returned by the next rendering step or tetray_finalize. */
int tetray_execute(tetray_adaptor* a, int64_t step, double time, int changes);
int tetray_get_report(const tetray_adaptor* a, tetray_report* report);
/* The name of skipped scene `index` (0 <= index < report.scenes_skipped) of the last
 * tetray_execute, valid until the next one. */
int tetray_get_skipped_scene(const tetray_adaptor* a, int index, const char** name);

/* Collective; drains the image writer and returns its error on every rank. tetray_destroy
 * finalizes if needed, then frees. */
int tetray_finalize(tetray_adaptor* a);
void tetray_destroy(tetray_adaptor* a);

/* The message of the last call on this thread, "" when it returned TETRAY_OK. */
const char* tetray_last_error(void);

#ifdef __cplusplus
}
#endif

#endif /* TETRAY_ADAPTOR_H */
