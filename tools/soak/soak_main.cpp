// tetray-soak: a long run through the public adaptor API that shows whether memory or file
// descriptors leak. Renders the deforming gyroid-twist scene (docs/architecture.md §6) at every
// step, points moving each step and the topology declared changed every --rebuild-every steps (so
// refit and rebuild both run), into tiny images, through the writer thread, as a solver would.
// Prints resident memory (VmRSS), its peak (VmHWM) and the open descriptors at intervals: a table,
// and with --json the same figures as a JSON object.
#include <mpi.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "render/core/stopwatch.hpp"
#include "scenes/box_mesh.hpp"
#include "tetray/adaptor.hpp"
#include "tools/bench_common/json_file.hpp"
#include "tools/soak/process_usage.hpp"

namespace {

using tetray::tools::ProcessUsage;

struct Options {
  int steps = 5000;
  int n = 12;
  int size = 32;
  int every = 500;
  int rebuild_every = 100;
  int queue_depth = 2;
  std::string out = "out/soak";
  std::string json;
};

struct Sample {
  int step = 0;  // steps rendered so far
  double seconds = 0;
  ProcessUsage usage;
};

constexpr const char* kScene = "soak";

std::string config(const Options& o) {
  std::ostringstream yaml;
  yaml << "output: {directory: " << o.out << ", quiet: true, writer_queue_depth: " << o.queue_depth
       << "}\nscenes:\n"
       << "  - {name: " << kScene << ", field: f, isovalues: [0],\n"
       << "     camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40},\n"
       << "     image: {width: " << o.size << ", height: " << o.size << "}}\n";
  return yaml.str();
}

// The files an earlier soak left, so that every soak measures a first run into its directory.
void remove_earlier_outputs(const Options& o) {
  namespace fs = std::filesystem;
  const fs::path out(o.out);
  for (const fs::path& p :
       {out / kScene, out / (std::string(kScene) + ".cdb"), out / "tetray_log.csv"}) {
    fs::remove_all(p);
  }
}

// Renders o.steps steps; false (after a message) when a call fails.
bool soak(const Options& o, std::vector<Sample>& samples, std::size_t& tets) {
  tetray::Status status;
  auto adaptor = tetray::Adaptor::create_from_yaml(MPI_COMM_WORLD, config(o), status);
  if (!adaptor) {
    std::fprintf(stderr, "tetray-soak: %s\n", status.message.c_str());
    return false;
  }
  const tetray::GyroidTwist scene = tetray::make_gyroid_twist(o.n, 0.0);
  tets = scene.mesh.tet_count();
  std::vector<double> points = scene.mesh.points, field = scene.field;
  const tetray::render::Stopwatch clock;
  for (int step = 0; step < o.steps && status.ok(); ++step) {
    const double t = 0.01 * step;
    tetray::deform_gyroid_twist(scene.mesh, t, points, field);
    const tetray::MeshView mesh{
        tetray::PointsView::of(points),
        tetray::TetsView::of(std::span<const std::int64_t>(scene.mesh.tets))};
    const tetray::FieldView fields[] = {tetray::FieldView::of("f", field)};
    const tetray::Changes changes{true, step % o.rebuild_every == 0, true};
    status = adaptor->execute(step, t, mesh, fields, changes);
    const int done = step + 1;
    if (done == 1 || done % o.every == 0 || done == o.steps) {
      samples.push_back({done, clock.ms() * 1e-3, tetray::tools::process_usage()});
    }
  }
  if (status.ok()) status = adaptor->finalize();
  if (!status.ok()) std::fprintf(stderr, "tetray-soak: %s\n", status.message.c_str());
  return status.ok();
}

void print(const Options& o, std::size_t tets, const std::vector<Sample>& samples) {
  std::printf(
      "tetray-soak: gyroid-twist n=%d (%zu tets), %dx%d, %d rendered steps, writer queue "
      "depth %d\n",
      o.n, tets, o.size, o.size, o.steps, o.queue_depth);
  std::printf("  %8s %10s %12s %12s %9s\n", "step", "seconds", "VmRSS kB", "VmHWM kB", "open fds");
  for (const Sample& s : samples) {
    std::printf("  %8d %10.2f %12llu %12llu %9zu\n", s.step, s.seconds,
                static_cast<unsigned long long>(s.usage.rss_kb),
                static_cast<unsigned long long>(s.usage.peak_rss_kb), s.usage.open_fds);
  }
  const Sample& first = samples.front();
  const Sample& last = samples.back();
  std::printf(
      "  after step %d -> %d: VmRSS %+lld kB, VmHWM %+lld kB, open fds %+lld\n", first.step,
      last.step,
      static_cast<long long>(last.usage.rss_kb) - static_cast<long long>(first.usage.rss_kb),
      static_cast<long long>(last.usage.peak_rss_kb) -
          static_cast<long long>(first.usage.peak_rss_kb),
      static_cast<long long>(last.usage.open_fds) - static_cast<long long>(first.usage.open_fds));
}

bool write_json(const Options& o, std::size_t tets, const std::vector<Sample>& samples) {
  using tetray::bench::count;
  Json::Value json;
  json["n"] = o.n;
  json["tets"] = count(tets);
  json["width"] = o.size;
  json["steps"] = o.steps;
  json["writer_queue_depth"] = o.queue_depth;
  json["samples"] = Json::Value(Json::arrayValue);
  for (const Sample& s : samples) {
    Json::Value sample;
    sample["step"] = s.step;
    sample["seconds"] = tetray::bench::number(s.seconds);
    sample["rss_kb"] = count(s.usage.rss_kb);
    sample["peak_rss_kb"] = count(s.usage.peak_rss_kb);
    sample["open_fds"] = count(s.usage.open_fds);
    json["samples"].append(sample);
  }
  return tetray::bench::write_json_file(json, o.json);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  CLI::App app{"tetray-soak: memory and file descriptors over a long rendered run"};
  Options o;
  app.add_option("--steps", o.steps, "rendered steps")->check(CLI::Range(1, 10'000'000));
  app.add_option("-n", o.n, "gyroid-twist resolution (6 n^3 tets)")->check(CLI::Range(1, 200));
  app.add_option("--size", o.size, "image width and height")->check(CLI::Range(1, 4096));
  app.add_option("--every", o.every, "steps between samples")->check(CLI::PositiveNumber);
  app.add_option("--rebuild-every", o.rebuild_every, "steps between declared topology changes")
      ->check(CLI::PositiveNumber);
  app.add_option("--queue-depth", o.queue_depth, "writer queue depth (0 writes in execute)")
      ->check(CLI::Range(0, 64));
  app.add_option("--out", o.out, "output directory (its earlier soak outputs are removed)");
  app.add_option("--json", o.json, "also write the figures to this JSON file");
  int code = 0;
  try {
    app.parse(argc, argv);
    remove_earlier_outputs(o);
    std::vector<Sample> samples;
    std::size_t tets = 0;
    if (!soak(o, samples, tets)) {
      code = 1;
    } else {
      print(o, tets, samples);
      if (!o.json.empty() && !write_json(o, tets, samples)) {
        std::fprintf(stderr, "tetray-soak: cannot write %s\n", o.json.c_str());
        code = 1;
      }
    }
  } catch (const CLI::ParseError& e) {
    code = app.exit(e);
  }
  MPI_Finalize();
  return code;
}
