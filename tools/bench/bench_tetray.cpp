#include "bench_tetray.hpp"

#include "bench_timing.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {
namespace {

// Each timed build starts from a copy of the loaded volume, whose tets are in the loaded BVH's
// leaf order: the order a rebuild in situ sees.
double build_ms(const render::TetVolume& loaded, render::BvhBuilder builder) {
  render::TetVolume volume;
  const render::BvhBuildOptions options{builder, render::BvhBuildOptions{}.leaf_size};
  return best_ms(
      kRepetitions, [&] { volume = loaded; }, [&] { render::build_bvh(volume, options); });
}

double bytes_per_tet(const render::TetVolume& volume, const render::Bvh& bvh) {
  const std::size_t ids = volume.tet_ids.size() * sizeof(std::uint32_t);
  return static_cast<double>(bvh.bytes() + ids) / static_cast<double>(volume.tets.size());
}

// Timing runs keep statistics off; the counts come from one extra run with them on. Every
// frame goes into the same image, as frames do in situ (so does the Embree reference's).
PacketFigures measure_packet(const render::TetVolume& volume, const render::Bvh& bvh,
                             const render::Camera& camera, render::PacketSize packet) {
  PacketFigures figures;
  figures.packet = packet;
  render::Framebuffer image;
  trace_scene(volume, bvh, camera, packet, image);
  figures.trace_ms =
      best_ms(kRepetitions, [&] { trace_scene(volume, bvh, camera, packet, image); });
  const double rays = static_cast<double>(camera.width) * camera.height;
  figures.mrays_per_s = rays / (figures.trace_ms * 1e3);
  trace_scene(volume, bvh, camera, packet, image, &figures.counts);
  return figures;
}

}  // namespace

TetrayRun measure_tetray(const GyroidTwist& scene, const render::Camera& camera) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  TetrayRun run;
  TetrayFigures& figures = run.figures;
  figures.build_bih_ms = build_ms(volume, render::BvhBuilder::bih);
  figures.build_sah_ms = build_ms(volume, render::BvhBuilder::sah);
  figures.bvh_bytes_per_tet = bytes_per_tet(volume, bvh);
  figures.volume_bytes_per_tet =
      static_cast<double>(volume.bytes()) / static_cast<double>(volume.tets.size());
  figures.bvh_nodes = bvh.nodes.size();
  for (const render::PacketSize packet : render::kPacketSizes)
    figures.packets.push_back(measure_packet(volume, bvh, camera, packet));
  trace_scene(volume, bvh, camera, render::PacketSize::p16x16, run.image);
  return run;
}

}  // namespace tetray::bench
