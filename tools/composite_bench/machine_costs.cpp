#include "tools/composite_bench/machine_costs.hpp"

#include <tbb/global_control.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "render/composite/composite_codec.hpp"
#include "tools/composite_bench/bench_images.hpp"

namespace tetray::composite_bench {
namespace {

using render::Framebuffer;

// One-way time of a message of `bytes` between ranks 0 and 1 of `pair` (half the round trip);
// only they call it.
double ping_pong(MPI_Comm pair, int rank, std::size_t bytes, int repeat) {
  std::vector<char> buffer(bytes);
  const int count = static_cast<int>(bytes);
  const double start = MPI_Wtime();
  for (int k = 0; k < repeat; ++k) {
    if (rank == 0) {
      MPI_Send(buffer.data(), count, MPI_CHAR, 1, 0, pair);
      MPI_Recv(buffer.data(), count, MPI_CHAR, 1, 0, pair, MPI_STATUS_IGNORE);
    } else {
      MPI_Recv(buffer.data(), count, MPI_CHAR, 0, 0, pair, MPI_STATUS_IGNORE);
      MPI_Send(buffer.data(), count, MPI_CHAR, 0, 0, pair);
    }
  }
  return (MPI_Wtime() - start) / (2.0 * repeat);
}

// The thread's CPU time with one thread; with several (--threads), the wall-clock time, which
// the work on the other threads takes too: the other ranks sleep meanwhile (measure_machine).
double work_seconds() {
  timespec now{};
  // In parentheses: the host's own clock, also under SMPI, whose wrapper makes clock_gettime a
  // macro for the simulated time.
  const bool threads =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
  (clock_gettime)(threads ? CLOCK_MONOTONIC : CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// The best of a few runs: first-touch page faults and (with one thread) other processes sharing
// the cores (oversubscribed runs) do not count.
template <typename Work>
double seconds_of(Work&& work) {
  double best = INFINITY;
  for (int run = 0; run < 3; ++run) {
    const double start = work_seconds();
    work();
    best = std::min(best, work_seconds() - start);
  }
  return best;
}

// CPU time per pixel of taking `message` into a fresh copy of `target` with `take_in`
// (composite_piece or copy_piece), best of three.
template <typename TakeIn>
double seconds_per_pixel(const Framebuffer& target, const render::PieceMessage& message,
                         TakeIn&& take_in) {
  Framebuffer image;
  double best = INFINITY;
  for (int run = 0; run < 3; ++run) {
    image = target;
    best = std::min(best, seconds_of([&] { take_in(image, message); }));
  }
  return best / static_cast<double>(target.pixel_count());
}

// The compositor's kernels at `size` squared: the activity scan of a nearly empty image (its
// worst case), then encoding a dense piece, and compositing and copying it into another.
PixelCosts measure_pixel_costs(int size) {
  Framebuffer nearly_empty(size, size);
  nearly_empty.depth.back() = 1.0f;
  const Framebuffer image = bench_image(Coverage::dense, size, 0, 2);
  const Framebuffer target = bench_image(Coverage::dense, size, 1, 2);
  const auto pixels = static_cast<double>(image.pixel_count());
  const render::PixelSpan all{0, static_cast<std::uint32_t>(image.pixel_count())};
  const render::PixelRect rect = render::active_rect(image);
  PixelCosts costs;
  render::PixelRect scanned;
  render::PieceMessage message;
  costs.scan = seconds_of([&] { scanned = render::active_rect(nearly_empty); }) / pixels;
  costs.encode = seconds_of([&] { message = render::encode_piece(image, all, rect); }) / pixels;
  costs.composite = seconds_per_pixel(target, message, [](Framebuffer& into, const auto& piece) {
    return render::composite_piece(into, piece);
  });
  costs.copy = seconds_per_pixel(target, message, [](Framebuffer& into, const auto& piece) {
    return render::copy_piece(into, piece);
  });
  return costs;
}

}  // namespace

void sleeping_barrier(MPI_Comm comm) {
#ifdef TETRAY_SMPI
  MPI_Barrier(comm);
#else
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  int done = 0;
  while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
#endif
}

MachineCosts measure_machine(MPI_Comm world, int size) {
  int rank = 0;
  MPI_Comm_rank(world, &rank);
  MachineCosts costs;
  // Ranks 0 and 1 of `world` itself: splitting off a pair is a collective whose cost grows
  // steeply with the rank count in the simulator.
  // The simulator's times have no noise, and every message costs host time in proportion to
  // the ranks waiting meanwhile: one round trip each there.
#ifdef TETRAY_SMPI
  constexpr int kSmallTrips = 1, kLargeTrips = 1, kWarmUpTrips = 0;
#else
  constexpr int kSmallTrips = 20000, kLargeTrips = 20, kWarmUpTrips = 1000;
#endif
  if (rank < 2) {
    if (kWarmUpTrips > 0) ping_pong(world, rank, 8, kWarmUpTrips);
    costs.latency_s = ping_pong(world, rank, 8, kSmallTrips);
    constexpr std::size_t kLarge = std::size_t{16} << 20;
    costs.bandwidth_Bps = static_cast<double>(kLarge) / ping_pong(world, rank, kLarge, kLargeTrips);
  }
  if (rank == 0) costs.pixel = measure_pixel_costs(size);
  sleeping_barrier(world);
  double shared[] = {costs.latency_s,    costs.bandwidth_Bps,   costs.pixel.scan,
                     costs.pixel.encode, costs.pixel.composite, costs.pixel.copy};
  MPI_Bcast(shared, 6, MPI_DOUBLE, 0, world);
  return {shared[0], shared[1], {shared[2], shared[3], shared[4], shared[5]}};
}

}  // namespace tetray::composite_bench
