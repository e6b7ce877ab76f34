#include "minisolver/study.hpp"

#include <cmath>
#include <fstream>
#include <functional>

#include "minisolver/log_log_plot.hpp"
#include "minisolver/manufactured_run.hpp"

namespace minisolver {
namespace {

constexpr double kEndTime = 0.5;
const Vec3 kDirection{1.0, 0.5, -0.25};
const ElasticMaterial kMaterial{1.0, 0.3, 1.0};

// One scheme of the ladder: its name and how it runs on a mesh with n cells per side.
struct Rung {
  std::string scheme;
  std::function<double(const LocalMesh&, int n)> time_step;
  std::function<RunResult(const LocalMesh&, double dt)> run;
};

std::vector<Rung> heat_rungs(const Comm& comm) {
  const Separable field{Shape::sine, Profile::oscillating};
  auto runner = [&comm, field](ThetaScheme scheme) {
    return [&comm, field, scheme](const LocalMesh& mesh, double dt) {
      return run_manufactured_heat(mesh, comm, scheme, dt, kEndTime, field);
    };
  };
  return {{"backward_euler", [](const LocalMesh&, int n) { return 0.08 * std::pow(4.0 / n, 2); },
           runner(ThetaScheme::backward_euler)},
          {"crank_nicolson", [](const LocalMesh&, int n) { return 0.1 * 4.0 / n; },
           runner(ThetaScheme::crank_nicolson)}};
}

std::vector<Rung> elastic_rungs(const Comm& comm) {
  const ElasticData data = manufactured_elastic({Shape::sine, Profile::oscillating}, kDirection,
                                                kMaterial.lame(), kMaterial.density);
  auto runner = [&comm, data](ElasticScheme scheme) {
    return [&comm, data, scheme](const LocalMesh& mesh, double dt) {
      return run_manufactured_elastic(mesh, comm, scheme, dt, kEndTime, data, kMaterial);
    };
  };
  return {{"newmark", [](const LocalMesh&, int n) { return 0.1 * 4.0 / n; },
           runner(ElasticScheme::newmark)},
          {"central_difference",
           [&comm](const LocalMesh& mesh, int) {
             return 0.9 * central_difference_limit(mesh, comm, {kMaterial}).dt;
           },
           runner(ElasticScheme::central_difference)}};
}

}  // namespace

std::vector<StudyRow> run_study(StudyProblem problem, const Comm& comm, int levels,
                                std::string& error) {
  const std::vector<Rung> rungs =
      problem == StudyProblem::heat ? heat_rungs(comm) : elastic_rungs(comm);
  std::vector<StudyRow> rows;
  for (const Rung& rung : rungs)
    for (int level = 0, n = 4; level < levels; ++level, n *= 2) {
      const LocalMesh mesh = distribute(make_beam({n, n, n}, {0, 0, 0}, {1, 1, 1}), comm);
      const double dt = rung.time_step(mesh, n);
      const RunResult r = rung.run(mesh, dt);
      if (!r.ok) {
        error = rung.scheme + " on n = " + std::to_string(n) + ": " + r.message;
        return rows;
      }
      rows.push_back({rung.scheme, n, 1.0 / n, kEndTime / steps_to_reach(kEndTime, dt), comm.size(),
                      r.seconds, r.error.l2, r.error.max});
    }
  return rows;
}

std::vector<double> l2_orders(const std::vector<StudyRow>& rows, const std::string& scheme) {
  std::vector<double> orders;
  const StudyRow* previous = nullptr;
  for (const StudyRow& row : rows) {
    if (row.scheme != scheme) continue;
    if (previous)
      orders.push_back(std::log(previous->l2_error / row.l2_error) / std::log(previous->h / row.h));
    previous = &row;
  }
  return orders;
}

bool write_study_csv(const std::string& path, const std::vector<StudyRow>& rows,
                     std::string& error) {
  std::ofstream out(path);
  out << "scheme,cells,h,dt,ranks,wall_seconds,l2_error,max_error\n";
  out.precision(9);
  for (const StudyRow& r : rows)
    out << r.scheme << ',' << r.cells << ',' << r.h << ',' << r.dt << ',' << r.ranks << ','
        << r.seconds << ',' << r.l2_error << ',' << r.max_error << '\n';
  out.close();
  if (out) return true;
  error = "cannot write " + path;
  return false;
}

bool plot_study(const std::string& path, const std::vector<StudyRow>& rows, std::string& error) {
  std::vector<PlotSeries> series;
  for (const StudyRow& r : rows) {
    if (series.empty() || series.back().label != r.scheme) series.push_back({r.scheme, {}});
    series.back().points.push_back({r.seconds, r.l2_error});
  }
  return write_log_log_plot(path, series, "WALL TIME S", "L2 ERROR", error);
}

}  // namespace minisolver
