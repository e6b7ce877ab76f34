// tetray-adaptor-bench: what the adaptor costs the solver on the gyroid-twist scene
// (docs/architecture.md §6): the adaptor's own overhead per rendered step (validation, conversion,
// bookkeeping: the blocked time minus refit and trace) against refit + trace; the cost of an
// off-trigger execute; and the time a rendered step blocks the solver with and without the writer
// thread, every step rendered; the encoding time and file size of each image format and
// compression on the image the run wrote. Prints a table, and with --json the same figures.
#include <mpi.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "render/core/stopwatch.hpp"
#include "scenes/box_mesh.hpp"
#include "tetray/adaptor.hpp"
#include "tools/adaptor_bench/encode_figures.hpp"
#include "tools/bench_common/json_file.hpp"

namespace {

struct Options {
  int n = 56;
  int steps = 10;
  long off_calls = 1'000'000;
  int size = 1024;
  std::string out = "out/adaptor_bench";
  std::string json;
  // The writer's keys (README, "Encoding"); empty or 0: the config's defaults.
  std::string exr_compression;
  int png_compression = -1;
  int writer_threads = 0;
  bool mp4 = false;
  int encode_runs = 5;
};

// One rendered step as the solver sees it and as the log splits it.
struct StepTimes {
  double blocked_ms = 0, solver_ms = 0, check_ms = 0, ingest_ms = 0, bvh_ms = 0, trace_ms = 0,
         queue_wait_ms = 0, encode_ms = 0, write_ms = 0;
  double render_ms() const { return bvh_ms + trace_ms; }
  double overhead_ms() const { return blocked_ms - render_ms() - queue_wait_ms; }
};

std::string output_keys(const Options& o) {
  std::ostringstream keys;
  if (!o.exr_compression.empty()) keys << ", exr_compression: " << o.exr_compression;
  if (o.png_compression >= 0) keys << ", png_compression: " << o.png_compression;
  if (o.writer_threads > 0) keys << ", writer_threads: " << o.writer_threads;
  if (o.mp4) keys << ", formats: [exr, png, mp4]";
  return keys.str();
}

std::string config(const Options& o, const std::string& dir, int queue_depth, int every) {
  std::ostringstream yaml;
  yaml << "output: {directory: " << dir << ", quiet: true, writer_queue_depth: " << queue_depth
       << output_keys(o) << "}\ntrigger: {every: " << every << "}\nscenes:\n"
       << "  - {name: gyroid, field: f, isovalues: [0],\n"
       << "     camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40},\n"
       << "     image: {width: " << o.size << ", height: " << o.size << "}}\n";
  return yaml.str();
}

std::unique_ptr<tetray::Adaptor> make(const std::string& yaml) {
  tetray::Status status;
  auto adaptor = tetray::Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status);
  if (!adaptor) std::fprintf(stderr, "tetray-adaptor-bench: %s\n", status.message.c_str());
  return adaptor;
}

// Column `name` of every data row of a CSV.
std::vector<double> column(const std::string& path, const std::string& name) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream head(line);
  for (std::string c; std::getline(head, c, ',');) header.push_back(c);
  const auto index =
      static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string c;
    for (std::size_t k = 0; k <= index && std::getline(row, c, ','); ++k) {
    }
    values.push_back(std::stod(c));
  }
  return values;
}

// Renders `o.steps` steps of the deforming gyroid; returns the per-step times.
std::vector<StepTimes> rendered_steps(const Options& o, const tetray::GyroidTwist& scene,
                                      const std::string& dir, int queue_depth) {
  std::filesystem::remove_all(dir);  // a run appends to an earlier run's log: start without one
  auto adaptor = make(config(o, dir, queue_depth, 1));
  if (!adaptor) return {};
  std::vector<double> points = scene.mesh.points, field = scene.field;
  std::vector<StepTimes> times(static_cast<std::size_t>(o.steps));
  for (int step = 0; step < o.steps; ++step) {
    const double t = 0.1 * step;
    const tetray::render::Stopwatch solver;
    tetray::deform_gyroid_twist(scene.mesh, t, points, field);  // the solver's own step
    times[static_cast<std::size_t>(step)].solver_ms = solver.ms();
    const tetray::MeshView mesh{
        tetray::PointsView::of(points),
        tetray::TetsView::of(std::span<const std::int64_t>(scene.mesh.tets))};
    const tetray::FieldView fields[] = {tetray::FieldView::of("f", field)};
    tetray::ExecuteReport report;
    const tetray::Status status =
        adaptor->execute(step, t, mesh, fields, {true, step == 0, true}, &report);
    if (!status.ok()) std::fprintf(stderr, "tetray-adaptor-bench: %s\n", status.message.c_str());
    times[static_cast<std::size_t>(step)].blocked_ms = report.seconds_blocked * 1e3;
  }
  adaptor->finalize();
  const std::string log = dir + "/tetray_log.csv";
  const auto fill = [&](const char* name, double StepTimes::*member) {
    const auto values = column(log, name);
    for (std::size_t k = 0; k < std::min(values.size(), times.size()); ++k)
      times[k].*member = values[k];
  };
  fill("check_ms", &StepTimes::check_ms);
  fill("ingest_ms", &StepTimes::ingest_ms);
  fill("bvh_ms", &StepTimes::bvh_ms);
  fill("trace_ms", &StepTimes::trace_ms);
  fill("queue_wait_ms", &StepTimes::queue_wait_ms);
  fill("encode_ms", &StepTimes::encode_ms);
  fill("write_ms", &StepTimes::write_ms);
  return times;
}

// Mean over the refit steps (all but the first, which builds the BVH).
StepTimes steady_mean(const std::vector<StepTimes>& steps) {
  StepTimes mean;
  const double n = static_cast<double>(std::max<std::size_t>(steps.size(), 2) - 1);
  for (std::size_t k = 1; k < steps.size(); ++k) {
    const StepTimes& s = steps[k];
    mean.blocked_ms += s.blocked_ms / n;
    mean.solver_ms += s.solver_ms / n;
    mean.check_ms += s.check_ms / n;
    mean.ingest_ms += s.ingest_ms / n;
    mean.bvh_ms += s.bvh_ms / n;
    mean.trace_ms += s.trace_ms / n;
    mean.queue_wait_ms += s.queue_wait_ms / n;
    mean.encode_ms += s.encode_ms / n;
    mean.write_ms += s.write_ms / n;
  }
  return mean;
}

double off_trigger_ns(const Options& o, const tetray::GyroidTwist& scene, const std::string& dir) {
  auto adaptor = make(config(o, dir, 2, 1'000'000'000));
  if (!adaptor) return 0;
  const tetray::MeshView mesh{tetray::PointsView::of(std::span<const double>(scene.mesh.points)),
                              tetray::TetsView::of(std::span<const std::int64_t>(scene.mesh.tets))};
  const tetray::FieldView fields[] = {
      tetray::FieldView::of("f", std::span<const double>(scene.field))};
  const tetray::render::Stopwatch watch;
  for (long step = 1; step <= o.off_calls; ++step) {
    adaptor->execute(step, static_cast<double>(step), mesh, fields, {true, false, true});
  }
  const double ns = watch.ms() * 1e6;
  adaptor->finalize();
  return ns / static_cast<double>(o.off_calls);
}

// The writer's run against the run that writes inside execute, and the encoding figures.
struct Results {
  std::size_t tets = 0;
  StepTimes writer, inline_;
  double off_ns = 0;
  std::vector<tetray::bench::EncodeFigure> encoding;
};

void print(const Options& o, const Results& r) {
  const StepTimes& w = r.writer;
  const double render_ms = w.render_ms();
  std::printf("tetray-adaptor-bench: gyroid-twist n=%d (%zu tets), %dx%d, mean of steps 1..%d\n",
              o.n, r.tets, o.size, o.size, o.steps - 1);
  std::printf("  writer: %s\n", output_keys(o).empty() ? "defaults" : output_keys(o).c_str() + 2);
  std::printf("  %-44s %10.3f ms\n", "refit + trace", render_ms);
  std::printf("  %-44s %10.3f ms  (%.1f%% of refit + trace; target < 10%%)\n",
              "adaptor overhead (blocked - refit - trace)", w.overhead_ms(),
              100 * w.overhead_ms() / render_ms);
  std::printf("  %-44s %10.3f ms\n", "  of which validation (check)", w.check_ms);
  std::printf("  %-44s %10.3f ms\n", "  of which conversion (ingest)", w.ingest_ms);
  std::printf("  %-44s %10.1f ns  (target < 1000 ns)\n", "off-trigger execute", r.off_ns);
  std::printf("  %-44s %10.3f ms\n", "solver's own step (between executes)", w.solver_ms);
  std::printf("  %-44s %10.3f ms  (%.1f%% over refit + trace; target <= 5%%)\n",
              "blocked per step, writer thread", w.blocked_ms,
              100 * (w.blocked_ms / render_ms - 1));
  std::printf("  %-44s %10.3f ms  (%.1f%% of refit + trace)\n",
              "  of which waiting for the writer's queue", w.queue_wait_ms,
              100 * w.queue_wait_ms / render_ms);
  std::printf("  %-44s %10.3f ms  (encode %.1f ms, write %.1f ms)\n", "  writer's time per step",
              w.encode_ms + w.write_ms, w.encode_ms, w.write_ms);
  std::printf("  %-44s %10.3f ms  (encode %.1f ms, write %.1f ms)\n",
              "blocked per step, writing in execute", r.inline_.blocked_ms, r.inline_.encode_ms,
              r.inline_.write_ms);
  std::printf("  encoding the last image, one thread, best of %d:\n", o.encode_runs);
  for (const tetray::bench::EncodeFigure& f : r.encoding) {
    std::printf("    %-4s %-22s %9.2f ms %11zu bytes  %s\n", f.format.c_str(),
                f.compression.c_str(), f.ms, f.bytes, f.note.c_str());
  }
}

Json::Value step_json(const StepTimes& s) {
  using tetray::bench::number;
  Json::Value j;
  j["blocked_ms"] = number(s.blocked_ms);
  j["solver_ms"] = number(s.solver_ms);
  j["refit_trace_ms"] = number(s.render_ms());
  j["overhead_ms"] = number(s.overhead_ms());
  j["check_ms"] = number(s.check_ms);
  j["ingest_ms"] = number(s.ingest_ms);
  j["queue_wait_ms"] = number(s.queue_wait_ms);
  j["encode_ms"] = number(s.encode_ms);
  j["write_ms"] = number(s.write_ms);
  return j;
}

bool write_json(const Options& o, const Results& r) {
  using tetray::bench::number;
  Json::Value j;
  j["n"] = o.n;
  j["tets"] = tetray::bench::count(r.tets);
  j["width"] = o.size;
  j["steps"] = o.steps;
  j["writer_keys"] = output_keys(o).empty() ? "defaults" : output_keys(o).substr(2);
  j["off_trigger_ns"] = number(r.off_ns);
  j["writer_thread"] = step_json(r.writer);
  j["writer_thread"]["blocked_over_render_percent"] =
      number(100 * (r.writer.blocked_ms / r.writer.render_ms() - 1));
  j["inline_write"] = step_json(r.inline_);
  for (const tetray::bench::EncodeFigure& f : r.encoding) {
    Json::Value e;
    e["format"] = f.format;
    e["compression"] = f.compression;
    e["lossless"] = f.lossless;
    e["note"] = f.note;
    e["ms"] = number(f.ms);
    e["bytes"] = tetray::bench::count(f.bytes);
    j["encoding"].append(e);
  }
  return tetray::bench::write_json_file(j, o.json);
}

// The last image the writer's run wrote.
std::string last_exr(const Options& o) {
  char name[64];
  std::snprintf(name, sizeof name, "gyroid/gyroid_%06d.exr", o.steps - 1);
  return o.out + "/writer_thread/" + name;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  CLI::App app{"tetray-adaptor-bench: adaptor overhead, off-trigger cost, writer, encoding"};
  Options o;
  app.add_option("-n", o.n, "gyroid-twist resolution (6 n^3 tets)");
  app.add_option("--steps", o.steps, "rendered steps (the first builds the BVH)")
      ->check(CLI::Range(2, 100));
  app.add_option("--off-calls", o.off_calls, "off-trigger execute calls to average");
  app.add_option("--size", o.size, "image width and height");
  app.add_option("--out", o.out, "output directory (images and logs)");
  app.add_option("--json", o.json, "also write the figures to this JSON file");
  app.add_option("--exr-compression", o.exr_compression, "output.exr_compression of the runs");
  app.add_option("--png-compression", o.png_compression, "output.png_compression of the runs");
  app.add_option("--writer-threads", o.writer_threads, "output.writer_threads of the runs");
  app.add_flag("--mp4", o.mp4, "the runs also write a movie");
  app.add_option("--encode-runs", o.encode_runs, "timings per encoding figure (the best counts)")
      ->check(CLI::Range(1, 100));
  int code = 0;
  try {
    app.parse(argc, argv);
    const tetray::GyroidTwist scene = tetray::make_gyroid_twist(o.n, 0.0);
    Results r;
    r.tets = scene.mesh.tet_count();
    r.writer = steady_mean(rendered_steps(o, scene, o.out + "/writer_thread", 2));
    r.inline_ = steady_mean(rendered_steps(o, scene, o.out + "/inline", 0));
    r.off_ns = off_trigger_ns(o, scene, o.out + "/off_trigger");
    std::string error;
    if (const auto image = tetray::bench::read_exr_image(last_exr(o), error)) {
      r.encoding = tetray::bench::encode_figures(*image, {0, 1, 2, 4, 6}, o.encode_runs, o.out);
    } else {
      std::fprintf(stderr, "tetray-adaptor-bench: %s\n", error.c_str());
      code = 1;
    }
    print(o, r);
    if (!o.json.empty() && !write_json(o, r)) {
      std::fprintf(stderr, "tetray-adaptor-bench: cannot write %s\n", o.json.c_str());
      code = 1;
    }
  } catch (const CLI::ParseError& e) {
    code = app.exit(e) == 0 ? 0 : 1;  // README: 1 on a usage error, 0 for --help
  }
  MPI_Finalize();
  return code;
}
