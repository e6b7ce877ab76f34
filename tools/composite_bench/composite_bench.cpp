// tetray-composite-bench: depth-compositing time, bytes and memory per rank for dense and sparse
// images (bench_images.hpp) at several rank counts, with every algorithm; the point-to-point
// latency and bandwidth (ping-pong) and the per-pixel costs of this machine.
//
//   mpirun --oversubscribe --allow-run-as-root -np 8 tetray-composite-bench [--json FILE]
//
// Each rank count P runs on the first P ranks of the job; the others wait in a sleeping poll so
// that they leave the cores to the ranks being measured. Built against SimGrid's SMPI
// (-DTETRAY_SMPI=ON, scripts/scaling.sh) the same program runs the compositor at thousands of
// simulated ranks; --model composites images that know only where their pixels are, with the
// computation injected from the per-pixel costs (model_image.hpp), for sizes and rank counts
// whose framebuffers would not fit this machine.
#include <mpi.h>

// SMPI's compiler wrapper defines exit(x) as a macro, which would rewrite CLI11's App::exit.
#ifdef TETRAY_SMPI
#undef exit
#endif

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "render/composite/composite.hpp"
#include "render/composite/composite_plan.hpp"
#include "render/composite/compositor.hpp"
#include "tools/composite_bench/bench_images.hpp"
#include "tools/composite_bench/bench_rows.hpp"
#include "tools/composite_bench/fragment_rows.hpp"
#include "tools/composite_bench/machine_costs.hpp"
#include "tools/composite_bench/model_image.hpp"

namespace tetray::composite_bench {
namespace {

using render::CompositeAlgorithm;
using render::CompositeRows;
using render::CompositeStats;

constexpr double kPixelBytes = render::kPixelWords * sizeof(std::uint32_t);

struct BenchOptions {
  std::vector<int> sizes{1024, 2048};
  std::vector<int> rank_counts{2, 4, 8};
  std::vector<Coverage> coverages{Coverage::dense, Coverage::sparse};
  std::vector<CompositeAlgorithm> algorithms{
      CompositeAlgorithm::binary_swap, CompositeAlgorithm::radix_k, CompositeAlgorithm::gather};
  std::vector<CompositeRows> row_orders{CompositeRows::automatic};
  int repeat = 5;
  bool model = false;
  bool hint = true;
  int byte_scale = 1;
  std::vector<double> costs_ns;  // scan, encode, composite[, copy]; measured when empty
  int cost_size = 1024;
  bool fragments = true;  // the transparent rows (fragment_rows.hpp), with real images only
  int threads = 1;        // per rank, for the fragments' merge (the depth compositor uses one)
  std::string json;
};

const std::map<std::string, CompositeAlgorithm> kAlgorithms{
    {"automatic", CompositeAlgorithm::automatic},
    {"binary_swap", CompositeAlgorithm::binary_swap},
    {"radix_k", CompositeAlgorithm::radix_k},
    {"gather", CompositeAlgorithm::gather}};

const std::map<std::string, CompositeRows> kRowOrders{{"automatic", CompositeRows::automatic},
                                                      {"natural", CompositeRows::natural},
                                                      {"interlaced", CompositeRows::interlaced}};

const char* algorithm_name(CompositeAlgorithm algorithm) {
  for (const auto& [name, value] : kAlgorithms) {
    if (value == algorithm) return name.c_str();
  }
  return "?";
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// One composite of a fresh copy of this rank's image; the stats of this rank.
// `hint`: the rank's footprint, as the adaptor passes the screen bound of its mesh.
// Both keep their receive buffers between runs, as the adaptor does between steps.
struct RealImage {
  const render::Framebuffer& image;
  std::optional<render::PixelRect> hint;
  render::Framebuffer last;  // the result of the last run (the root's image)
  render::CompositeWorkspace workspace;
  int composite(MPI_Comm comm, CompositeAlgorithm algorithm, CompositeRows rows,
                CompositeStats& stats) {
    last = image;
    return render::composite(last, comm, {algorithm, 0, hint, rows}, &stats, &workspace);
  }
};

struct ModelRun {
  ModelImage image;
  std::optional<render::PixelRect> hint;
  render::CompositeWorkspace workspace;
  int composite(MPI_Comm comm, CompositeAlgorithm algorithm, CompositeRows rows,
                CompositeStats& stats) {
    ModelImage copy = image;
    return render::composite_image(copy, true, comm, {algorithm, 0, hint, rows}, stats, workspace);
  }
};

// The slowest rank's end of each round, over `comm` (a rank that handed on early has none for
// the later rounds).
std::vector<double> slowest_round_ends(const CompositeStats& stats, MPI_Comm comm) {
  std::vector<double> ends(static_cast<std::size_t>(stats.rounds), -1.0);
  for (std::size_t k = 0; k < ends.size() && k < stats.round_seconds.size(); ++k) {
    ends[k] = 1e3 * stats.round_seconds[k];
  }
  MPI_Allreduce(MPI_IN_PLACE, ends.data(), static_cast<int>(ends.size()), MPI_DOUBLE, MPI_MAX,
                comm);
  return ends;
}

// Times `repeat` composites over `comm` (collective on comm).
template <typename Run>
Row measure(Run& run, int size, MPI_Comm comm, CompositeAlgorithm algorithm, CompositeRows rows,
            int repeat) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<double> times;
  std::vector<std::vector<double>> round_ends;
  CompositeStats stats;
  for (int k = 0; k < repeat; ++k) {
    MPI_Barrier(comm);
    if (run.composite(comm, algorithm, rows, stats) != MPI_SUCCESS) MPI_Abort(comm, 1);
    double slowest = stats.seconds;
    MPI_Allreduce(MPI_IN_PLACE, &slowest, 1, MPI_DOUBLE, MPI_MAX, comm);
    times.push_back(slowest * 1e3);
    round_ends.push_back(slowest_round_ends(stats, comm));
  }
  const double sent = static_cast<double>(stats.bytes_sent);
  const double moved = sent + static_cast<double>(stats.bytes_received);
  const double pixels = double(size) * size;
  double maxima[] = {sent, moved, static_cast<double>(stats.peak_message_bytes) / pixels};
  double moved_sum = moved;
  MPI_Allreduce(MPI_IN_PLACE, maxima, 3, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &moved_sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  Row row;
  row.ranks = ranks;
  row.size = size;
  row.algorithm = algorithm_name(algorithm);
  row.rows = stats.interlaced ? "interlaced" : "natural";
  row.rounds = stats.rounds;
  row.median_ms = median(times);
  row.min_ms = *std::min_element(times.begin(), times.end());
  const auto median_run = std::find(times.begin(), times.end(), row.median_ms) - times.begin();
  row.round_end_ms = round_ends[static_cast<std::size_t>(median_run)];
  // The fold and the radix rounds come first; the rest assemble the image on the root.
  const render::CompositePlan plan = render::make_plan(ranks, algorithm);
  const std::size_t proper = (plan.folded_count() > 0 ? 1 : 0) + plan.radices.size();
  row.composite_ms = proper == 0 ? 0.0 : row.round_end_ms[proper - 1];
  row.assembly_ms = row.median_ms - row.composite_ms;
  row.sent_max = maxima[0];
  row.moved_max = maxima[1];
  row.message_bytes_per_pixel = maxima[2];
  row.moved_mean = moved_sum / ranks;
  row.bound = 2.0 * (1.0 - 1.0 / ranks) * pixels * kPixelBytes;
  return row;
}

std::vector<Row> measure_rank_count(int ranks, const BenchOptions& options,
                                    const ModelSettings& settings, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<Row> rows;
  for (int size : options.sizes) {
    for (Coverage coverage : options.coverages) {
      for (CompositeAlgorithm algorithm : options.algorithms) {
        for (CompositeRows order : options.row_orders) {
          const render::PixelRect covered = footprint(coverage, size, rank, ranks);
          std::optional<render::PixelRect> hint;
          if (options.hint) hint = covered;
          if (options.model) {
            ModelRun run{{size, size, {covered}, &settings}, hint, {}};
            rows.push_back(measure(run, size, comm, algorithm, order, options.repeat));
          } else {
            const render::Framebuffer image = bench_image(coverage, size, rank, ranks);
            RealImage run{image, hint, {}, {}};
            rows.push_back(measure(run, size, comm, algorithm, order, options.repeat));
            rows.back().root_image_hash = rank == 0 ? image_hash(run.last) : 0;
          }
          rows.back().coverage = coverage_name(coverage);
          rows.back().model = options.model;
        }
      }
    }
  }
  return rows;
}

int run(const BenchOptions& options) {
  int rank = 0, world_size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  if (world_size < 2) {
    if (rank == 0) std::fprintf(stderr, "tetray-composite-bench: run it with 2 ranks or more\n");
    return 1;
  }
#ifndef TETRAY_SMPI
  // A model piece travels as an address: it means something only where all ranks share one
  // process, as they do in the simulator.
  if (options.model) {
    if (rank == 0) {
      std::fprintf(stderr,
                   "tetray-composite-bench: --model needs the simulator's build "
                   "(-DTETRAY_SMPI=ON, scripts/scaling.sh)\n");
    }
    return 1;
  }
#endif
  MachineCosts costs = measure_machine(MPI_COMM_WORLD, options.cost_size);
  if (!options.costs_ns.empty()) {
    // Without a copy cost the assembly is charged as compositing, as before copies existed.
    const double copy_ns = options.costs_ns.size() > 3 ? options.costs_ns[3] : options.costs_ns[2];
    costs.pixel = {options.costs_ns[0] * 1e-9, options.costs_ns[1] * 1e-9,
                   options.costs_ns[2] * 1e-9, copy_ns * 1e-9};
  }
  const ModelSettings settings{costs.pixel, options.byte_scale};
  std::vector<Row> rows;
  std::vector<FragmentRow> fragment_rows;
  for (int ranks : options.rank_counts) {
    if (ranks > world_size) continue;
    // The whole job as it is where it is measured whole (the simulator runs one count per job):
    // a split is a collective whose cost grows steeply with the rank count there.
    MPI_Comm comm = MPI_COMM_WORLD;
    if (ranks < world_size) {
      MPI_Comm_split(MPI_COMM_WORLD, rank < ranks ? 0 : MPI_UNDEFINED, rank, &comm);
    }
    if (comm != MPI_COMM_NULL) {
      const std::vector<Row> measured = measure_rank_count(ranks, options, settings, comm);
      rows.insert(rows.end(), measured.begin(), measured.end());
      if (options.fragments && !options.model) {
        const std::vector<FragmentRow> transparent =
            measure_fragments(options.sizes, options.coverages, options.repeat, comm);
        fragment_rows.insert(fragment_rows.end(), transparent.begin(), transparent.end());
      }
      if (comm != MPI_COMM_WORLD) MPI_Comm_free(&comm);
    }
    sleeping_barrier(MPI_COMM_WORLD);
  }
  if (rank != 0) return 0;
  print_costs(costs);
  print_rows(rows);
  print_fragment_rows(fragment_rows);
  if (!options.json.empty() && !write_json(options.json, rows, costs, fragment_rows)) {
    std::fprintf(stderr, "tetray-composite-bench: cannot write %s\n", options.json.c_str());
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace tetray::composite_bench

int main(int argc, char** argv) {
  using namespace tetray::composite_bench;
  MPI_Init(&argc, &argv);
  BenchOptions options;
  CLI::App app{"tetray-composite-bench: depth compositing time, bytes and memory per rank"};
  app.add_option("--sizes", options.sizes, "square image sizes in pixels")
      ->check(CLI::Range(1, 16384));
  app.add_option("--ranks", options.rank_counts, "rank counts to measure (at most the job's)")
      ->check(CLI::Range(2, 1 << 20));
  app.add_option("--coverage", options.coverages,
                 "dense, sparse (a cube seen along z), sparse_x (along x); default dense sparse")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, Coverage>{{"dense", Coverage::dense},
                                          {"sparse", Coverage::sparse},
                                          {"sparse_x", Coverage::sparse_x}}));
  app.add_option("--algorithms", options.algorithms, "automatic, binary_swap, radix_k, gather")
      ->transform(CLI::CheckedTransformer(kAlgorithms));
  app.add_option("--rows", options.row_orders,
                 "row orders of the schedule: automatic (default), natural, interlaced")
      ->transform(CLI::CheckedTransformer(kRowOrders));
  app.add_option("--repeat", options.repeat, "runs per measurement (median reported)")
      ->check(CLI::Range(1, 1000));
  app.add_flag("--model", options.model,
               "composite model images (where the pixels are, costs injected): for the simulator");
  app.add_flag("--hint,!--no-hint", options.hint,
               "tell the compositor each rank's footprint (default), as the adaptor does");
  app.add_option("--byte-scale", options.byte_scale,
                 "model messages this many times shorter on the wire (divide the bandwidth alike)")
      ->check(CLI::Range(1, 1 << 20));
  app.add_option("--costs-ns", options.costs_ns,
                 "per-pixel scan, encode, composite and copy costs for the model (default: "
                 "measured; without copy, the composite cost)")
      ->expected(3, 4)
      ->check(CLI::PositiveNumber);
  app.add_option("--cost-size", options.cost_size, "image size at which to measure the costs")
      ->check(CLI::Range(16, 8192));
  app.add_flag("--fragments,!--no-fragments", options.fragments,
               "also composite each image as transparent layers (fragments) against opaque "
               "(default; not with --model)");
  app.add_option("--threads", options.threads,
                 "threads per rank that merge the fragments (default 1: one rank per core, as "
                 "the depth compositor runs)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--json", options.json, "also write the figures to this JSON file");
  int status = 0;
  try {
    app.parse(argc, argv);
    const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                      static_cast<std::size_t>(options.threads));
    status = run(options);
  } catch (const CLI::ParseError& error) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    // README: 1 on a usage error, 0 for --help; only rank 0 prints.
    status = (rank == 0 ? app.exit(error) : error.get_exit_code()) == 0 ? 0 : 1;
  }
  MPI_Finalize();
  return status;
}
