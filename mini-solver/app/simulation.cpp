#include "simulation.hpp"

#include <tetray/adaptor.hpp>

#include <memory>
#include <optional>

#include "mesh_input.hpp"
#include "minisolver/point_fields.hpp"
#include "minisolver/solver_config.hpp"
#include "run_report.hpp"

namespace minisolver {
namespace {

struct Physics {
  std::unique_ptr<HeatSolver> heat;
  std::unique_ptr<ElasticSolver> elastic;
};

HeatData hot_faces(double temperature) {
  // Zero everywhere at the start, then the fixed faces at `temperature` from the first step on.
  return {[temperature](const Vec3&, double t) { return t > 0 ? temperature : 0.0; },
          [](const Vec3&, double) { return 0.0; }};
}

ElasticData constant_load(const Vec3& force) {
  return {[](const Vec3&, double) { return Kinematics{}; },
          [force](const Vec3&, double) { return force; }};
}

std::optional<Physics> make_physics(const SolverConfig& config, const LocalMesh& mesh,
                                    const Comm& comm, std::string& error) {
  Physics physics;
  if (config.heat)
    physics.heat = std::make_unique<HeatSolver>(mesh, comm, config.heat->setup,
                                                hot_faces(config.heat->hot_temperature));
  if (config.elasticity) {
    physics.elastic = ElasticSolver::create(mesh, comm, config.elasticity->setup,
                                            constant_load(config.elasticity->body_force), error);
    if (!physics.elastic) return std::nullopt;
  }
  return physics;
}

// The point fields of the current state, in the storage the views point into.
struct RenderFields {
  std::vector<double> temperature, displacement_magnitude, von_mises, interior;

  std::vector<tetray::FieldView> views() const {
    std::vector<tetray::FieldView> v{tetray::FieldView::of("interior", interior)};
    if (!temperature.empty()) v.push_back(tetray::FieldView::of("temperature", temperature));
    if (!von_mises.empty()) {
      v.push_back(tetray::FieldView::of("displacement_magnitude", displacement_magnitude));
      v.push_back(tetray::FieldView::of("von_mises", von_mises));
    }
    return v;
  }
};

RenderFields render_fields(const Physics& physics, const SolverConfig& config,
                           const LocalMesh& mesh, const DofSpace& scalar_space) {
  RenderFields f;
  f.interior = interior_indicator(mesh);
  if (physics.heat)
    f.temperature.assign(physics.heat->temperature().begin(), physics.heat->temperature().end());
  if (physics.elastic) {
    f.displacement_magnitude = magnitudes(physics.elastic->displacement());
    f.von_mises =
        average_to_points(scalar_space, von_mises_per_tet(mesh, config.elasticity->setup.materials,
                                                          physics.elastic->displacement()));
  }
  return f;
}

class Run {
 public:
  Run(const SolverConfig& config, const LocalMesh& mesh, const Comm& comm, Physics physics,
      tetray::Adaptor& adaptor)
      : config_(config),
        mesh_(mesh),
        comm_(comm),
        physics_(std::move(physics)),
        adaptor_(adaptor),
        scalar_space_(mesh, comm, 1) {}

  int loop() {
    if (!hand_over(0, 0.0)) return exit_adaptor;
    for (int step = 1; step <= config_.steps; ++step) {
      if (!advance(step)) return exit_stopped;
      if (!hand_over(step, step * config_.dt)) return exit_adaptor;
    }
    say(comm_, "done: " + std::to_string(config_.steps) + " steps, " + std::to_string(rendered_) +
                   " rendered" + displacement_summary());
    return exit_ok;
  }

  // The execute calls' blocked time (ExecuteReport::seconds_blocked, the log's blocked_ms).
  double seconds_in_adaptor() const { return seconds_in_adaptor_; }

 private:
  // How far the body moved by the end, for elasticity runs: finite and bounded is what a stable
  // scheme owes, whatever dt. Collective.
  std::string displacement_summary() const {
    if (!physics_.elastic) return {};
    const double largest = scalar_space_.max_abs(magnitudes(physics_.elastic->displacement()));
    return "; largest displacement " + std::to_string(largest);
  }

  bool advance(int step) {
    std::string iterations;
    for (const StepOutcome& outcome :
         {physics_.heat ? physics_.heat->step() : StepOutcome{},
          physics_.elastic ? physics_.elastic->step() : StepOutcome{}}) {
      if (!outcome.ok) {
        say(comm_, "stopped at step " + std::to_string(step) + ": " + outcome.message);
        return false;
      }
      iterations.append(1, ' ').append(std::to_string(outcome.iterations));
    }
    last_iterations_ = iterations;
    return true;
  }

  bool hand_over(int step, double time) {
    if (!adaptor_.will_render(step, time)) return execute(step, time, {});
    const RenderFields fields = render_fields(physics_, config_, mesh_, scalar_space_);
    const bool ok = execute(step, time, fields.views());
    say(comm_, "step " + std::to_string(step) + " t = " + std::to_string(time) +
                   " CG iterations (heat, elasticity):" + last_iterations_);
    return ok;
  }

  // False when the adaptor failed. Its status is the same on every rank, so every rank leaves
  // the time loop at the same step (a rank that went on alone would wait forever in the next
  // halo exchange). A partial step (some scenes skipped) is reported and the run goes on.
  bool execute(int step, double time, const std::vector<tetray::FieldView>& fields) {
    tetray::MeshView view;
    view.points = tetray::PointsView::of(std::span<const double>(mesh_.points));
    if (physics_.elastic) view.points.displacement = physics_.elastic->displacement().data();
    view.tets = tetray::TetsView::of(std::span<const std::int32_t>(mesh_.tets));
    view.tets.global_ids = mesh_.tet_ids.data();
    const tetray::Changes changes{step == 0 || physics_.elastic != nullptr, step == 0, true};
    tetray::ExecuteReport report;
    const tetray::Status status = adaptor_.execute(step, time, view, fields, changes, &report);
    seconds_in_adaptor_ += report.seconds_blocked;
    rendered_ += report.rendered ? 1 : 0;
    if (!status.ok()) say(comm_, "tetray: " + status.message);
    return !status.failed();
  }

  const SolverConfig& config_;
  const LocalMesh& mesh_;
  const Comm& comm_;
  Physics physics_;
  tetray::Adaptor& adaptor_;
  DofSpace scalar_space_;
  std::string last_iterations_;
  double seconds_in_adaptor_ = 0;
  int rendered_ = 0;
};

bool load(const std::string& path, SolverConfig& config, std::string& tetray_yaml,
          std::string& error) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    error = path + ": " + e.what();
    return false;
  }
  if (!parse_run_config(root, config, tetray_yaml, error)) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

}  // namespace

int run_simulation(const std::string& config_path, MPI_Comm world) {
  const Seconds wall;
  const MpiComm comm(world);
  SolverConfig config;
  std::string tetray_yaml, error;
  if (!load(config_path, config, tetray_yaml, error)) {
    say(comm, error);
    return exit_config;
  }
  tetray::Status status;
  const Seconds creating;
  const auto adaptor = tetray::Adaptor::create_from_yaml(world, tetray_yaml, status);
  // The time tetray blocks the run: create, every execute and finalize (which drains the writer).
  double blocked = creating.elapsed();
  if (!adaptor) {
    say(comm, config_path + ": tetray section: " + status.message);
    return exit_config;
  }
  if (!config.partition_weights.empty() &&
      config.partition_weights.size() != static_cast<std::size_t>(comm.size())) {
    say(comm, config_path + ": solver.partition.weights: give one weight per rank (" +
                  std::to_string(comm.size()) + ")");
    return exit_config;
  }
  const LocalMesh mesh = distribute(make_mesh(config), comm, config.partition_weights);
  report_mesh(config, mesh, comm);
  if (config.elasticity) report_locking(config.elasticity->setup, comm);
  std::optional<Physics> physics = make_physics(config, mesh, comm, error);
  if (!physics) {
    say(comm, "refused: " + error);
    adaptor->finalize();
    return exit_refused;
  }
  if (physics->elastic) report_time_step(*physics->elastic, config.elasticity->setup, comm);
  Run run(config, mesh, comm, std::move(*physics), *adaptor);
  const int code = run.loop();
  // Collective, so every rank gets the writer's last errors and exits with the same code.
  const Seconds finalizing;
  const tetray::Status finalized = adaptor->finalize();
  blocked += finalizing.elapsed() + run.seconds_in_adaptor();
  if (!finalized.ok()) say(comm, "tetray finalize: " + finalized.message);
  report_blocked(comm, wall.elapsed(), blocked);
  if (finalized.failed() && code == exit_ok) return exit_adaptor;
  return code;
}

}  // namespace minisolver
