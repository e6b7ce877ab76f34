// tetray-isa-bench: the frame and refit time of each instruction-set variant of a dispatch build
// on the gyroid-twist benchmark scene (docs/architecture.md §6, camera and isovalue of
// tetray-bench), in tiles and in 32x32 and 16x16 packets. The variants take turns within each
// round, so a shared machine's load changes disturb all of them alike; each figure is the best over
// the rounds. A native or portable build times its one variant, for comparison with a dispatch
// build's.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "render/core/stopwatch.hpp"
#include "render/isa/isa.hpp"
#include "render/trace/trace.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray {
namespace {

struct Figures {
  std::string name;
  double frame_tiled_ms = std::numeric_limits<double>::infinity();
  double frame_32_ms = std::numeric_limits<double>::infinity();
  double frame_16_ms = std::numeric_limits<double>::infinity();
  double refit_ms = std::numeric_limits<double>::infinity();
};

template <typename Work>
void keep_best(double& best, Work&& work) {
  const render::Stopwatch watch;
  work();
  best = std::min(best, watch.ms());
}

// One round of the active variant: a frame in tiles and per packet size, and a refit of the
// geometry.
void time_round(render::TetVolume& volume, render::Bvh& bvh, const render::Camera& camera,
                render::Framebuffer& image, Figures& figures) {
  const render::IsoSurface surface = bench::bench_surface();
  const auto time_frame = [&](render::PacketSize packet, double& best) {
    render::TraceOptions options;
    options.packet = packet;
    keep_best(best, [&] {
      render::trace_into(image, volume, bvh, camera, {&surface, 1}, options);
    });
  };
  time_frame(render::PacketSize::tiled, figures.frame_tiled_ms);
  time_frame(render::PacketSize::p32x32, figures.frame_32_ms);
  time_frame(render::PacketSize::p16x16, figures.frame_16_ms);
  keep_best(figures.refit_ms, [&] { render::refit_bvh(volume, bvh, true); });
}

// The variants to time: every one the CPU supports in a dispatch build, else the build's one.
std::vector<render::isa::Isa> variants() {
  std::vector<render::isa::Isa> isas;
  for (render::isa::Isa isa : render::isa::kIsas)
    if (render::isa::cpu_supports(isa)) isas.push_back(isa);
  if (!render::isa::dispatched()) isas = {render::isa::active()};
  return isas;
}

int run(int n, int size_px, int rounds) {
  if (const std::string lacks = render::isa::kernels_refusal(); !lacks.empty()) {
    std::fprintf(stderr, "tetray-isa-bench: %s\n", lacks.c_str());
    return 1;
  }
  const GyroidTwist scene = make_gyroid_twist(n, 0.2);
  render::TetVolume volume;
  render::Bvh bvh;
  bench::load_scene(scene, volume, bvh);
  const render::Camera camera = bench::bench_camera(size_px);
  render::Framebuffer image;

  const std::string choice = render::isa::choice_note();  // before the bench activates each
  const std::vector<render::isa::Isa> isas = variants();
  std::vector<Figures> figures(isas.size());
  for (std::size_t k = 0; k < isas.size(); ++k) {
    figures[k].name = render::isa::dispatched() ? render::isa::to_string(isas[k]) : "the one";
  }
  // Round 0 is the warm-up of each variant and is not kept.
  for (int round = 0; round <= rounds; ++round) {
    for (std::size_t k = 0; k < isas.size(); ++k) {
      render::isa::activate(isas[k]);
      Figures warm_up;
      time_round(volume, bvh, camera, image, round == 0 ? warm_up : figures[k]);
    }
  }
  std::printf("tetray-isa-bench: gyroid-twist n = %d, %zu tets, %dx%d pixels, best of %d rounds\n",
              n, scene.mesh.tet_count(), size_px, size_px, rounds);
  std::printf("  kernels %s\n", choice.c_str());
  std::printf("  %-8s %10s %10s %10s %10s\n", "variant", "tiled ms", "32x32 ms", "16x16 ms",
              "refit ms");
  for (const Figures& f : figures) {
    std::printf("  %-8s %10.1f %10.1f %10.1f %10.2f\n", f.name.c_str(), f.frame_tiled_ms,
                f.frame_32_ms, f.frame_16_ms, f.refit_ms);
  }
  return 0;
}

}  // namespace
}  // namespace tetray

int main(int argc, char** argv) {
  CLI::App app{"tetray-isa-bench: frame and refit time per instruction-set variant"};
  int n = 56, size_px = 1024, rounds = 5;
  app.add_option("--size", n, "gyroid-twist resolution n (6 n^3 tets)")->check(CLI::Range(1, 400));
  app.add_option("--size-px", size_px, "image width and height")->check(CLI::Range(1, 16384));
  app.add_option("--rounds", rounds, "timed rounds after the warm-up")->check(CLI::Range(1, 1000));
  CLI11_PARSE(app, argc, argv);
  return tetray::run(n, size_px, rounds);
}
