// What one scene's render at one step did: the row of tetray_log.csv (docs/outputs.md, "The timing
// log"). Stages that did not run for this scene report 0 ms, so the log shows what a scene did not
// need. The columns from check_ms to other_ms cut the execute call into phases (PhaseClock,
// adaptor/step/phase_clock.hpp): summed over a step's rows they give its blocked_ms. Work done
// once per step (validation, agreements, probes, the rest) is in the step's first row.
#pragma once

#include <cstdint>
#include <string>

namespace tetray {

struct StepRecord {
  std::int64_t step = 0;
  double time = 0;
  std::string scene;
  int threads = 0;                  // the renderer's threads on each rank
  double check_ms = 0;              // validation of indices and values
  double ingest_ms = 0;             // adaptor-side conversion (connectivity, tie keys, keep mask)
  double bvh_ms = 0;                // fused ingest + refit, or rebuild
  std::string bvh_update = "none";  // none, field_refit, refit, rebuild
  double color_ms = 0;              // color field conversion and range (0 without color_by)
  double trace_ms = 0;
  double composite_ms = 0;   // 0 on one rank
  double agree_ms = 0;       // the agreements and reductions across ranks (waits for the slowest)
  double probes_ms = 0;      // probes located, gathered and appended
  double hand_off_ms = 0;    // the view's job for the writer (and a per-rank image, if asked for)
  double queue_wait_ms = 0;  // execute waiting for room in the writer queue
  double other_ms = 0;       // the rest of the call: trigger, bookkeeping between the stages
  double blocked_ms = 0;     // the whole execute call; the same in every row of the step
  double encode_ms = 0;      // EXR and PNG encoding, on the writer thread
  double write_ms = 0;       // atomic image writes and CSV appends, on the writer thread
  std::uint64_t tets = 0;    // all ranks
  std::uint64_t kept_tets = 0;     // rendered: not ghost, not skipped
  std::uint64_t skipped_tets = 0;  // under nonfinite: skip_tets
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;            // pixels with a surface in the composited image
  std::uint64_t bvh_bytes = 0;       // renderer copy + BVH, all ranks
  std::uint64_t peak_rss_bytes = 0;  // largest over ranks
};

// A simulated time as written in the CSV files (9 significant digits).
std::string time_text(double time);

// The CSV header and one row, in the same column order.
std::string log_header();
std::string log_row(const StepRecord& r);

}  // namespace tetray
