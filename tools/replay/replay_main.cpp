// tetray-replay: renders a saved series (a ParaView .pvd, or a list of .vtu/.pvtu files)
// through the same adaptor and config as a live run, so a config can be tuned offline. Rank 0
// reads every step; other ranks take part with no tets. A step that cannot be read renders
// nothing; a scene whose field a step lacks is skipped for that step. Exits non-zero if any step
// failed or rendered none of its due scenes. --output DIR writes where the config's
// output.directory would.
#include <mpi.h>
#include <yaml-cpp/yaml.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tetray/adaptor.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace {

using tetray::vtkio::SeriesEntry;

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The steps to replay: a .pvd's entries with their times, or the files with time = index.
bool list_series(const std::vector<std::string>& inputs, std::vector<SeriesEntry>& series,
                 std::string& error) {
  if (inputs.size() == 1 && ends_with(inputs[0], ".pvd")) {
    return tetray::vtkio::read_pvd(inputs[0], series, error);
  }
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    if (!ends_with(inputs[k], ".vtu") && !ends_with(inputs[k], ".pvtu")) {
      error = inputs[k] + ": expected a .pvd, or .vtu/.pvtu files";
      return false;
    }
    series.push_back({static_cast<double>(k), inputs[k]});
  }
  return true;
}

// Rank 0 reads the step into `grid`; every rank learns whether it could, so that a step that
// cannot be read is left out on every rank and writes no image.
bool read_step(const SeriesEntry& entry, int rank, tetray::vtkio::TetGrid& grid) {
  int read = 1;
  std::string error;
  if (rank == 0 && !tetray::vtkio::read_grid(entry.path, grid, error)) {
    std::fprintf(stderr, "tetray-replay: %s\n", error.c_str());
    read = 0;
  }
  MPI_Bcast(&read, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return read == 1;
}

// A step whose every due scene was skipped (a field name no step has, say) wrote nothing that
// was asked: the adaptor calls that partial, the replay a failure.
bool nothing_rendered(const tetray::Status& status, const tetray::ExecuteReport& report) {
  return status.code == tetray::StatusCode::partial && report.scenes_rendered == 0;
}

// Replays every step; a failed step is reported and the replay goes on. The adaptor's status is
// the same on every rank, so rank 0 alone prints it.
int replay(tetray::Adaptor& adaptor, const std::vector<SeriesEntry>& series,
           std::int64_t first_step, int rank) {
  int failed = 0;
  bool first = true;
  tetray::vtkio::TetGrid previous;
  for (std::size_t step = 0; step < series.size(); ++step) {
    tetray::vtkio::TetGrid grid;
    if (!read_step(series[step], rank, grid)) {
      ++failed;
      continue;
    }
    // Saved steps say nothing of what changed: compare with the previous step, so an unmoved
    // mesh gets a scalar-only refit and an unchanged topology no rebuild.
    const tetray::Changes changes{
        first || grid.points != previous.points,
        first || grid.tets != previous.tets || grid.ghost != previous.ghost, true};
    const std::int64_t number = first_step + static_cast<std::int64_t>(step);
    tetray::ExecuteReport report;
    const tetray::Status status =
        tetray::execute(adaptor, number, series[step].time, grid, changes, &report);
    if (!status.ok() && rank == 0) {
      std::fprintf(stderr, "tetray-replay: step %lld: %s%s\n", static_cast<long long>(number),
                   nothing_rendered(status, report) ? "no scene rendered: " : "",
                   status.message.c_str());
    }
    failed += status.failed() || nothing_rendered(status, report) ? 1 : 0;
    first = false;
    previous = std::move(grid);
  }
  const tetray::Status finalized = adaptor.finalize();
  if (!finalized.ok()) {
    if (rank == 0) std::fprintf(stderr, "tetray-replay: %s\n", finalized.message.c_str());
    ++failed;
  }
  return failed;
}

// The config file's YAML with output.directory set to `output`; nothing when yaml-cpp cannot
// read it as a map (with an `output` map, if any): the adaptor then reads the file as it is, and
// its message names the file and the line.
std::optional<std::string> with_output_directory(const std::string& config,
                                                 const std::string& output) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(config);
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
  if (!root.IsMap() || (root["output"] && !root["output"].IsMap())) return std::nullopt;
  root["output"]["directory"] = output;
  YAML::Emitter text;
  text << root;
  return std::string(text.c_str());
}

// The adaptor of the config file, writing to `output` when it is not empty.
std::unique_ptr<tetray::Adaptor> create_adaptor(const std::string& config,
                                                const std::string& output, tetray::Status& status) {
  const std::optional<std::string> yaml =
      output.empty() ? std::nullopt : with_output_directory(config, output);
  if (!yaml) return tetray::Adaptor::create(MPI_COMM_WORLD, config, status);
  auto adaptor = tetray::Adaptor::create_from_yaml(MPI_COMM_WORLD, *yaml, status);
  if (!adaptor) status.message = config + " with --output " + output + ": " + status.message;
  return adaptor;
}

int run(int argc, char** argv, int rank) {
  CLI::App app{"tetray-replay: render a saved .pvd or .vtu/.pvtu series with a tetray config"};
  std::string config;
  std::string output;
  std::vector<std::string> inputs;
  app.add_option("-c,--config", config, "YAML config (the adaptor's keys at the top level)")
      ->required();
  std::int64_t first_step = 0;
  app.add_option("-o,--output", output, "output directory, instead of the config's");
  app.add_option("--first-step", first_step,
                 "the step number of the series' first entry (the trigger and the file names "
                 "count from it)")
      ->capture_default_str();
  app.add_option("inputs", inputs, "a .pvd file, or .vtu/.pvtu files in step order")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;  // README: 1 on a usage error, 0 for --help
  }
  std::vector<SeriesEntry> series;
  std::string error;
  if (!list_series(inputs, series, error)) {
    if (rank == 0) std::fprintf(stderr, "tetray-replay: %s\n", error.c_str());
    return 2;
  }
  tetray::Status status;
  auto adaptor = create_adaptor(config, output, status);
  if (!adaptor) {
    if (rank == 0) std::fprintf(stderr, "tetray-replay: %s\n", status.message.c_str());
    return 2;
  }
  return replay(*adaptor, series, first_step, rank) == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int code = run(argc, argv, rank);
  MPI_Finalize();
  return code;
}
