// tetray-composite-bench: depth-compositing time and bytes per rank for dense and sparse
// images at several rank counts, against the binary-swap bound 2(1 - 1/P) x image size; the
// point-to-point latency and bandwidth (ping-pong) and the per-pixel costs of this machine; and
// a latency/bandwidth model of the compositing time at rank counts past this machine.
//
//   mpirun --oversubscribe --allow-run-as-root -np 8 tetray-composite-bench [--json FILE]
//
// Each rank count P runs on the first P ranks of the job; the others wait in a sleeping poll so
// that they leave the cores to the ranks being measured.
#include <mpi.h>

#include <time.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "render/composite/composite.hpp"
#include "render/composite/composite_codec.hpp"
#include "tools/bench_common/json_file.hpp"

namespace {

using tetray::render::CompositeAlgorithm;
using tetray::render::CompositeStats;
using tetray::render::Framebuffer;

constexpr double kPixelBytes = tetray::render::kPixelWords * sizeof(std::uint32_t);

struct BenchOptions {
  std::vector<int> sizes{1024, 2048};
  std::vector<int> rank_counts{2, 4, 8};
  int repeat = 5;
  std::string json;
};

struct Row {
  int ranks = 0;
  int size = 0;
  std::string mode, algorithm;
  int rounds = 0;
  double median_ms = 0, min_ms = 0;                    // slowest rank's time per run
  double sent_max = 0, moved_mean = 0, moved_max = 0;  // bytes per rank; moved = sent + received
  double bound = 0;                                    // 2 (1 - 1/P) x image bytes
};

// Point-to-point and per-pixel costs measured here, the inputs of the model.
struct MachineCosts {
  double latency_s = 0;              // one-way time of an 8-byte message
  double bandwidth_Bps = 0;          // of a 16 MiB message
  double scan_s_per_pixel = 0;       // finding the active rectangle
  double encode_s_per_pixel = 0;     // dense piece to message
  double composite_s_per_pixel = 0;  // message into an image
};

// A barrier whose waiting ranks sleep instead of spinning on the cores.
void sleeping_barrier(MPI_Comm comm) {
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  int done = 0;
  while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

// Dense: every pixel active. Sparse: rank r hits only cell r of a near-square grid of P cells,
// about 1/P of the screen.
Framebuffer bench_image(int size, bool sparse, int rank, int ranks) {
  Framebuffer image(size, size);
  const int columns = static_cast<int>(std::ceil(std::sqrt(ranks)));
  const int rows = (ranks + columns - 1) / columns;
  const int x0 = sparse ? size * (rank % columns) / columns : 0;
  const int x1 = sparse ? size * (rank % columns + 1) / columns : size;
  const int y0 = sparse ? size * (rank / columns) / rows : 0;
  const int y1 = sparse ? size * (rank / columns + 1) / rows : size;
  std::mt19937 rng(static_cast<std::uint32_t>(rank) + 1u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int j = y0; j < y1; ++j) {
    for (int i = x0; i < x1; ++i) {
      const std::size_t p = image.index(i, j);
      image.depth[p] = 1.0f + unit(rng);
      image.hit[p] = static_cast<std::uint32_t>(p) * static_cast<std::uint32_t>(ranks) +
                     static_cast<std::uint32_t>(rank);
      for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = unit(rng);
    }
  }
  return image;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

const char* algorithm_name(CompositeAlgorithm algorithm) {
  constexpr const char* kNames[] = {"automatic", "binary_swap", "radix_k", "gather"};
  return kNames[static_cast<int>(algorithm)];
}

// Times `repeat` composites of fresh copies of `image` over `comm` (collective on comm).
Row measure(const Framebuffer& image, MPI_Comm comm, CompositeAlgorithm algorithm, int repeat) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<double> times;
  CompositeStats stats;
  for (int run = 0; run < repeat; ++run) {
    Framebuffer copy = image;
    MPI_Barrier(comm);
    tetray::render::composite(copy, comm, {algorithm, 0}, &stats);
    double slowest = stats.seconds;
    MPI_Allreduce(MPI_IN_PLACE, &slowest, 1, MPI_DOUBLE, MPI_MAX, comm);
    times.push_back(slowest * 1e3);
  }
  const double sent = static_cast<double>(stats.bytes_sent);
  const double moved = sent + static_cast<double>(stats.bytes_received);
  double maxima[] = {sent, moved}, moved_sum = moved;
  MPI_Allreduce(MPI_IN_PLACE, maxima, 2, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &moved_sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  Row row;
  row.ranks = ranks;
  row.size = image.width;
  row.algorithm = algorithm_name(algorithm);
  row.rounds = stats.rounds;
  row.median_ms = median(times);
  row.min_ms = *std::min_element(times.begin(), times.end());
  row.sent_max = maxima[0];
  row.moved_max = maxima[1];
  row.moved_mean = moved_sum / ranks;
  row.bound = 2.0 * (1.0 - 1.0 / ranks) * static_cast<double>(image.pixel_count()) * kPixelBytes;
  return row;
}

std::vector<Row> measure_rank_count(int ranks, const BenchOptions& options, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<Row> rows;
  for (int size : options.sizes) {
    for (bool sparse : {false, true}) {
      const Framebuffer image = bench_image(size, sparse, rank, ranks);
      for (CompositeAlgorithm algorithm :
           {CompositeAlgorithm::binary_swap, CompositeAlgorithm::radix_k,
            CompositeAlgorithm::gather}) {
        rows.push_back(measure(image, comm, algorithm, options.repeat));
        rows.back().mode = sparse ? "sparse" : "dense";
      }
    }
  }
  return rows;
}

// One-way time of a message of `bytes` between ranks 0 and 1 (half the round trip).
double ping_pong(MPI_Comm world, int rank, std::size_t bytes, int repeat) {
  std::vector<char> buffer(bytes);
  const int count = static_cast<int>(bytes);
  MPI_Barrier(world);
  const double start = MPI_Wtime();
  for (int k = 0; k < repeat; ++k) {
    if (rank == 0) {
      MPI_Send(buffer.data(), count, MPI_CHAR, 1, 0, world);
      MPI_Recv(buffer.data(), count, MPI_CHAR, 1, 0, world, MPI_STATUS_IGNORE);
    } else {
      MPI_Recv(buffer.data(), count, MPI_CHAR, 0, 0, world, MPI_STATUS_IGNORE);
      MPI_Send(buffer.data(), count, MPI_CHAR, 0, 0, world);
    }
  }
  return (MPI_Wtime() - start) / (2.0 * repeat);
}

double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// CPU time of the best of a few runs: first-touch page faults and other processes sharing the
// cores (oversubscribed runs) do not count.
template <typename Work>
double seconds_of(Work&& work) {
  double best = INFINITY;
  for (int run = 0; run < 3; ++run) {
    const double start = thread_cpu_seconds();
    work();
    best = std::min(best, thread_cpu_seconds() - start);
  }
  return best;
}

// Per-pixel costs of the compositor's local work at `size` squared: the active-rectangle scan
// of a nearly empty image (its worst case), then encoding and compositing a dense piece.
void measure_pixel_costs(int size, MachineCosts& costs) {
  using namespace tetray::render;
  Framebuffer nearly_empty(size, size);
  nearly_empty.depth.back() = 1.0f;
  const Framebuffer image = bench_image(size, false, 0, 2);
  const Framebuffer target = bench_image(size, false, 1, 2);
  const auto pixels = static_cast<double>(image.pixel_count());
  const PixelSpan all{0, static_cast<std::uint32_t>(image.pixel_count())};
  PixelRect rect;
  PieceMessage message;
  costs.scan_s_per_pixel = seconds_of([&] { rect = active_rect(nearly_empty); }) / pixels;
  rect = active_rect(image);
  costs.encode_s_per_pixel = seconds_of([&] { message = encode_piece(image, all, rect); }) / pixels;
  Framebuffer composited;
  double composite_s = INFINITY;
  for (int run = 0; run < 3; ++run) {
    composited = target;
    composite_s = std::min(composite_s, seconds_of([&] { composite_piece(composited, message); }));
  }
  costs.composite_s_per_pixel = composite_s / pixels;
}

MachineCosts measure_machine(MPI_Comm world, int rank, int size) {
  MachineCosts costs;
  if (rank < 2) {
    MPI_Comm pair;
    MPI_Comm_split(world, 0, rank, &pair);
    ping_pong(pair, rank, 8, 1000);  // warm-up
    costs.latency_s = ping_pong(pair, rank, 8, 20000);
    constexpr std::size_t kLarge = std::size_t{16} << 20;
    costs.bandwidth_Bps = static_cast<double>(kLarge) / ping_pong(pair, rank, kLarge, 20);
    if (rank == 0) measure_pixel_costs(size, costs);
    MPI_Comm_free(&pair);
  } else {
    MPI_Comm none;
    MPI_Comm_split(world, MPI_UNDEFINED, rank, &none);
  }
  sleeping_barrier(world);
  return costs;
}

// Dense binary swap: log2 P rounds halving the piece, then P - 1 pieces into the root; sparse
// (each rank ~1/P of the screen): every round moves ~N/(2P) pixels per rank, and the root
// still receives the whole covered screen. Every rank first scans its image once.
struct ModelTime {
  double swap_ms = 0, gather_ms = 0, total_ms = 0;
};

ModelTime model(const MachineCosts& c, double ranks, double pixels, bool sparse) {
  const double per_pixel_wire = kPixelBytes / c.bandwidth_Bps;
  const double per_pixel_swap = per_pixel_wire + c.encode_s_per_pixel + c.composite_s_per_pixel;
  const double swapped =
      sparse ? std::log2(ranks) * pixels / (2 * ranks) : (1 - 1 / ranks) * pixels;
  const double gathered = sparse ? pixels : (1 - 1 / ranks) * pixels;
  ModelTime t;
  t.swap_ms = 1e3 * (pixels * c.scan_s_per_pixel + std::log2(ranks) * c.latency_s +
                     swapped * per_pixel_swap);
  t.gather_ms =
      1e3 * ((ranks - 1) * c.latency_s + gathered * (per_pixel_wire + c.composite_s_per_pixel));
  t.total_ms = t.swap_ms + t.gather_ms;
  return t;
}

void print_rows(const std::vector<Row>& rows) {
  std::printf("\n%5s %6s %-7s %-12s %6s %10s %10s %11s %12s %11s %9s\n", "P", "size", "mode",
              "algorithm", "rounds", "median ms", "min ms", "sent max MB", "moved mean MB",
              "bound MB", "mean/bnd");
  for (const Row& r : rows) {
    std::printf("%5d %6d %-7s %-12s %6d %10.2f %10.2f %11.2f %12.2f %11.2f %9.3f\n", r.ranks,
                r.size, r.mode.c_str(), r.algorithm.c_str(), r.rounds, r.median_ms, r.min_ms,
                r.sent_max / 1e6, r.moved_mean / 1e6, r.bound / 1e6, r.moved_mean / r.bound);
  }
}

void print_costs(const MachineCosts& c) {
  std::printf("ping-pong: latency %.2f us one way, bandwidth %.2f GB/s (16 MiB messages)\n",
              c.latency_s * 1e6, c.bandwidth_Bps / 1e9);
  std::printf("per pixel: scan %.2f ns, encode %.2f ns, composite %.2f ns (%g bytes on the wire)\n",
              c.scan_s_per_pixel * 1e9, c.encode_s_per_pixel * 1e9, c.composite_s_per_pixel * 1e9,
              kPixelBytes);
}

void print_model(const MachineCosts& costs, const BenchOptions& options) {
  std::printf("\nmodel, binary swap + gather to the root (measured costs above)\n");
  std::printf("%6s %6s %-7s %10s %10s %10s\n", "P", "size", "mode", "swap ms", "gather ms",
              "total ms");
  std::vector<int> model_ranks = options.rank_counts;
  model_ranks.insert(model_ranks.end(), {64, 1024, 16384});
  for (int size : options.sizes) {
    for (bool sparse : {false, true}) {
      for (int ranks : model_ranks) {
        const ModelTime t = model(costs, ranks, double(size) * size, sparse);
        std::printf("%6d %6d %-7s %10.2f %10.2f %10.2f\n", ranks, size, sparse ? "sparse" : "dense",
                    t.swap_ms, t.gather_ms, t.total_ms);
      }
    }
  }
}

bool write_json(const std::string& path, const std::vector<Row>& rows, const MachineCosts& c) {
  Json::Value json;
  json["latency_us"] = tetray::bench::number(c.latency_s * 1e6);
  json["bandwidth_GBps"] = tetray::bench::number(c.bandwidth_Bps / 1e9);
  json["scan_ns_per_pixel"] = tetray::bench::number(c.scan_s_per_pixel * 1e9);
  json["encode_ns_per_pixel"] = tetray::bench::number(c.encode_s_per_pixel * 1e9);
  json["composite_ns_per_pixel"] = tetray::bench::number(c.composite_s_per_pixel * 1e9);
  json["runs"] = Json::Value(Json::arrayValue);
  for (const Row& r : rows) {
    Json::Value run;
    run["ranks"] = r.ranks;
    run["size"] = r.size;
    run["mode"] = r.mode;
    run["algorithm"] = r.algorithm;
    run["rounds"] = r.rounds;
    run["median_ms"] = tetray::bench::number(r.median_ms);
    run["min_ms"] = tetray::bench::number(r.min_ms);
    run["sent_max_bytes"] = tetray::bench::number(r.sent_max);
    run["moved_mean_bytes"] = tetray::bench::number(r.moved_mean);
    run["moved_max_bytes"] = tetray::bench::number(r.moved_max);
    run["bound_bytes"] = tetray::bench::number(r.bound);
    json["runs"].append(run);
  }
  return tetray::bench::write_json_file(json, path);
}

int run(const BenchOptions& options) {
  int rank = 0, world_size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  if (world_size < 2) {
    if (rank == 0)
      std::fprintf(stderr, "tetray-composite-bench: run it with mpirun -np 2 or more\n");
    return 1;
  }
  const MachineCosts costs = measure_machine(
      MPI_COMM_WORLD, rank, *std::max_element(options.sizes.begin(), options.sizes.end()));
  std::vector<Row> rows;
  for (int ranks : options.rank_counts) {
    if (ranks > world_size) continue;
    MPI_Comm comm;
    MPI_Comm_split(MPI_COMM_WORLD, rank < ranks ? 0 : MPI_UNDEFINED, rank, &comm);
    if (comm != MPI_COMM_NULL) {
      const std::vector<Row> measured = measure_rank_count(ranks, options, comm);
      rows.insert(rows.end(), measured.begin(), measured.end());
      MPI_Comm_free(&comm);
    }
    sleeping_barrier(MPI_COMM_WORLD);
  }
  if (rank != 0) return 0;
  print_costs(costs);
  print_rows(rows);
  print_model(costs, options);
  if (!options.json.empty() && !write_json(options.json, rows, costs)) {
    std::fprintf(stderr, "tetray-composite-bench: cannot write %s\n", options.json.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  BenchOptions options;
  CLI::App app{"tetray-composite-bench: depth compositing time and bytes per rank"};
  app.add_option("--sizes", options.sizes, "square image sizes in pixels")
      ->check(CLI::Range(1, 16384));
  app.add_option("--ranks", options.rank_counts, "rank counts to measure (at most the job's)")
      ->check(CLI::Range(2, 1 << 20));
  app.add_option("--repeat", options.repeat, "runs per measurement (median reported)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--json", options.json, "also write the figures to this JSON file");
  int status = 0;
  try {
    app.parse(argc, argv);
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
