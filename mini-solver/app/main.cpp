// tetray-minisolver: a deforming P1 finite-element solver coupled to tetray like any outside
// code, or, with --study, the error-against-run-time study of its schemes.
//   mpirun -np 2 tetray-minisolver configs/demo.yaml
//   mpirun -np 2 tetray-minisolver --study heat --levels 4 --csv heat.csv --plot heat.png
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "minisolver/study.hpp"
#include "simulation.hpp"

namespace {

int run_study_mode(const std::string& problem, int levels, const std::string& csv,
                   const std::string& plot) {
  const minisolver::MpiComm comm(MPI_COMM_WORLD);
  const auto kind =
      problem == "heat" ? minisolver::StudyProblem::heat : minisolver::StudyProblem::elasticity;
  std::string error;
  const auto rows = minisolver::run_study(kind, comm, levels, error);
  if (comm.rank() != 0) return error.empty() ? 0 : minisolver::exit_stopped;
  std::printf("%-20s %6s %10s %10s %6s %10s %12s %12s\n", "scheme", "cells", "h", "dt", "ranks",
              "wall_s", "l2_error", "max_error");
  for (const auto& r : rows)
    std::printf("%-20s %6d %10.4g %10.4g %6d %10.4g %12.4e %12.4e\n", r.scheme.c_str(), r.cells,
                r.h, r.dt, r.ranks, r.seconds, r.l2_error, r.max_error);
  const bool written = (csv.empty() || minisolver::write_study_csv(csv, rows, error)) &&
                       (plot.empty() || minisolver::plot_study(plot, rows, error));
  if (!error.empty()) std::printf("study: %s\n", error.c_str());
  return written && error.empty() ? 0 : minisolver::exit_stopped;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "tetray-minisolver: deforming P1 finite-element solver with in-situ tetray rendering"};
  std::string config, study, csv, plot;
  int levels = 3;
  app.add_option("config", config, "YAML file with solver: and tetray: sections");
  app.add_option("--study", study, "error against run time instead of a run")
      ->check(CLI::IsMember({"heat", "elasticity"}));
  app.add_option("--levels", levels, "mesh levels of the study (n = 4, 8, 16, ...)")
      ->check(CLI::Range(2, 6));
  app.add_option("--csv", csv, "study rows as CSV");
  app.add_option("--plot", plot, "study work-precision plot (PNG)");
  CLI11_PARSE(app, argc, argv);
  if (config.empty() == study.empty()) {
    std::fprintf(stderr, "give either a config file or --study\n");
    return minisolver::exit_config;
  }
  MPI_Init(&argc, &argv);
  const int code = study.empty() ? minisolver::run_simulation(config, MPI_COMM_WORLD)
                                 : run_study_mode(study, levels, csv, plot);
  MPI_Finalize();
  return code;
}
