// The deal.II heat example coupled in situ to tetray: every step the solver advances (adapting
// its mesh every few steps), and tetray renders the temperature's isosurfaces on the steps its
// config's trigger selects, from the rank's own and ghost hexahedra, without copying the mesh to
// disk.
//
//   mpirun -np 2 dealii_heat_insitu [--config heat_insitu.yaml] [--steps 24] ...  (--help)
//
// Prints per step the solver's time (adaptation, assembly and CG) and, on a rendered step, the
// time spent building the views and the time tetray blocked; at the end the totals side by side.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include <tetray/adaptor.hpp>

#include "dealii_session.hpp"
#include "example_options.hpp"
#include "heat_problem.hpp"
#include "tetray_views.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Totals {
  double solver = 0, views = 0, create = 0, execute = 0, finalize = 0;
  int rendered = 0;
};

// The time loop; returns the exit code (the same on every rank: tetray's statuses agree).
int run(MPI_Comm comm, const ExampleOptions& options) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  Totals totals;
  auto started = std::chrono::steady_clock::now();
  tetray::Status status;
  const auto adaptor = tetray::Adaptor::create(comm, options.config, status);
  totals.create = seconds_since(started);
  if (!adaptor) {
    if (rank == 0) std::fprintf(stderr, "tetray: %s\n", status.message.c_str());
    return 1;
  }

  const HeatParameters& heat = options.heat;
  HeatProblem problem(comm, heat);
  LocalHexMesh mesh;
  bool mesh_exported = false;  // whether `mesh` holds the current mesh's cells and points
  for (unsigned int step = 1; step <= heat.steps; ++step) {
    const double time = step * heat.dt;
    started = std::chrono::steady_clock::now();
    const bool adapted = heat.refine_every > 0 && step % heat.refine_every == 0;
    if (adapted) {
      problem.adapt_mesh();
      mesh_exported = false;
    }
    const unsigned int iterations = problem.advance(time);
    const double solver_seconds = seconds_since(started);
    totals.solver += solver_seconds;

    // What is new since the last execute call: the mesh only after an adaptation (it never
    // moves), the temperature every step. tetray keeps the flags of the off-trigger calls, so a
    // topology change at a skipped step still rebuilds at the next rendered one.
    const bool new_mesh = step == 1 || adapted;
    const tetray::Changes changes{.geometry = new_mesh, .topology = new_mesh, .fields = true};
    tetray::ExecuteReport report;
    double views_seconds = 0;
    if (adaptor->will_render(step, time)) {
      started = std::chrono::steady_clock::now();
      if (!mesh_exported) problem.export_mesh(mesh);
      mesh_exported = true;
      problem.export_temperature(mesh);
      const tetray::FieldView fields[] = {temperature_view(mesh)};
      views_seconds = seconds_since(started);
      totals.views += views_seconds;
      status = adaptor->execute(step, time, hex_mesh_view(mesh, options.ghost_flags), fields,
                                changes, &report);
      ++totals.rendered;
    } else {
      // Off-trigger: no views are built; the call only records the changes (about 0.1 us).
      status = adaptor->execute(step, time, {}, {}, changes, &report);
    }
    totals.execute += report.seconds_blocked;

    const double peak = problem.max_temperature();
    const auto cells = static_cast<unsigned long long>(problem.global_cells());
    const auto hanging = static_cast<unsigned long long>(problem.hanging_nodes());
    if (rank == 0) {
      std::printf("step %3u t=%.3f cells %5llu%s hanging %4llu max u %.4f cg %2u solver %6.2f ms",
                  step, time, cells, adapted ? " (adapted)" : "          ", hanging, peak,
                  iterations, 1e3 * solver_seconds);
      if (report.rendered) {
        std::printf(" | views %5.2f ms, tetray %7.2f ms (%s)", 1e3 * views_seconds,
                    1e3 * report.seconds_blocked, report.bvh_decision.c_str());
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    if (status.failed()) {  // the same on every rank, so every rank stops here
      if (rank == 0) std::fprintf(stderr, "tetray: step %u: %s\n", step, status.message.c_str());
      return 1;
    }
    if (!status.ok() && rank == 0) std::fprintf(stderr, "tetray: %s\n", status.message.c_str());
  }

  started = std::chrono::steady_clock::now();
  status = adaptor->finalize();
  totals.finalize = seconds_since(started);
  if (rank == 0) {
    const double blocked = totals.create + totals.execute + totals.finalize;
    std::printf(
        "dealii_heat_insitu: solver %.3f s over %u steps (%.2f ms a step), views %.2f ms, "
        "blocked in tetray %.3f s (create %.3f, execute %.3f over %d rendered steps: %.2f ms "
        "each, finalize %.3f) = %.0f%% of the solver's time\n",
        totals.solver, heat.steps, 1e3 * totals.solver / heat.steps, 1e3 * totals.views, blocked,
        totals.create, totals.execute, totals.rendered,
        totals.rendered ? 1e3 * totals.execute / totals.rendered : 0.0, totals.finalize,
        100 * blocked / totals.solver);
  }
  if (status.failed()) {
    if (rank == 0) std::fprintf(stderr, "tetray: finalize: %s\n", status.message.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  DealiiSession session(argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::string error;
  const auto options = parse_options(argc, argv, error);
  if (!options) {
    if (rank == 0) std::fprintf(stderr, "%s", error.c_str());
    return 2;
  }
  if (options->help) {
    if (rank == 0) std::printf("%s", example_usage);
    return 0;
  }
  try {
    return run(MPI_COMM_WORLD, *options);
  } catch (const std::exception& e) {
    // A deal.II or Trilinos failure on one rank: the others may wait in a collective call.
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return 1;
}
