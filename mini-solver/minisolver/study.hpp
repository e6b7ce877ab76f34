// Error against run time: each problem is solved over a ladder of meshes (n = 4, 8, 16, ...
// cells per side of the unit cube) with time steps refined so that space and time errors fall
// together (dt ~ h^2 for first-order schemes, dt ~ h for second-order ones, dt at a fixed
// fraction of the CFL limit for central differences).
#pragma once

#include <string>
#include <vector>

#include "minisolver/comm.hpp"

namespace minisolver {

enum class StudyProblem { heat, elasticity };

struct StudyRow {
  std::string scheme;
  int cells = 0;
  double h = 0;
  double dt = 0;
  int ranks = 1;
  double seconds = 0;
  double l2_error = 0;
  double max_error = 0;
};

// Rows in ladder order per scheme; on a failed run, `error` is set and the rows so far returned.
std::vector<StudyRow> run_study(StudyProblem problem, const Comm& comm, int levels,
                                std::string& error);

// The observed order of the L2 error in h between consecutive rows of one scheme.
std::vector<double> l2_orders(const std::vector<StudyRow>& rows, const std::string& scheme);

bool write_study_csv(const std::string& path, const std::vector<StudyRow>& rows,
                     std::string& error);

// Log-log work-precision plot: L2 error against wall time, one line per scheme.
bool plot_study(const std::string& path, const std::vector<StudyRow>& rows, std::string& error);

}  // namespace minisolver
