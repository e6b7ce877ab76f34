// One row of tetray-composite-bench per (ranks, size, coverage, algorithm): times, bytes and
// memory, printed as a table and written as JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/composite_bench/fragment_rows.hpp"
#include "tools/composite_bench/machine_costs.hpp"

namespace tetray::composite_bench {

struct Row {
  int ranks = 0;
  int size = 0;
  std::string coverage, algorithm;
  std::string rows;    // the row order the compositor took: natural or interlaced
  bool model = false;  // a model image (model_image.hpp), not a real framebuffer
  int rounds = 0;
  double median_ms = 0, min_ms = 0;  // the slowest rank's time per run
  // The slowest rank's time at the end of each round of the median run (fold, radix rounds,
  // assembly steps): time per round is the difference of neighbours.
  std::vector<double> round_end_ms;
  // Of the median run: compositing proper (to the end of the last radix round, the image then
  // spread over the ranks in spans), and the assembly of the image on the root after it.
  double composite_ms = 0, assembly_ms = 0;
  double sent_max = 0, moved_mean = 0, moved_max = 0;  // bytes per rank; moved = sent + received
  double bound = 0;                                    // 2 (1 - 1/P) x image bytes
  // The most message bytes a rank held at once, per pixel of the image (the image itself holds
  // 24 bytes per pixel beside them).
  double message_bytes_per_pixel = 0;
  std::uint64_t root_image_hash = 0;  // of the root's composited image (real images only)
};

void print_costs(const MachineCosts& costs);
void print_rows(const std::vector<Row>& rows);
bool write_json(const std::string& path, const std::vector<Row>& rows, const MachineCosts& costs,
                const std::vector<FragmentRow>& fragments);

}  // namespace tetray::composite_bench
