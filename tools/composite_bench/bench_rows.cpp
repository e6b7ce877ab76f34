#include "tools/composite_bench/bench_rows.hpp"

#include <cinttypes>
#include <cstdio>
#include <string>

#include "tools/bench_common/json_file.hpp"

namespace tetray::composite_bench {

void print_costs(const MachineCosts& c) {
  std::printf("ping-pong: latency %.2f us one way, bandwidth %.2f GB/s (16 MiB messages)\n",
              c.latency_s * 1e6, c.bandwidth_Bps / 1e9);
  std::printf(
      "per pixel: scan %.2f ns, encode %.2f ns, composite %.2f ns, copy %.2f ns (24 bytes on the "
      "wire)\n",
      c.pixel.scan * 1e9, c.pixel.encode * 1e9, c.pixel.composite * 1e9, c.pixel.copy * 1e9);
}

void print_rows(const std::vector<Row>& rows) {
  std::printf("\n%6s %6s %-7s %-12s %-10s %-5s %6s %10s %10s %10s %11s %12s %9s %9s\n", "P", "size",
              "mode", "algorithm", "rows", "image", "rounds", "median ms", "rounds ms", "assembly",
              "sent max MB", "moved mean MB", "mean/bnd", "msg B/px");
  for (const Row& r : rows) {
    std::printf(
        "%6d %6d %-7s %-12s %-10s %-5s %6d %10.3f %10.3f %10.3f %11.2f %12.2f %9.3f %9.2f\n",
        r.ranks, r.size, r.coverage.c_str(), r.algorithm.c_str(), r.rows.c_str(),
        r.model ? "model" : "real", r.rounds, r.median_ms, r.composite_ms, r.assembly_ms,
        r.sent_max / 1e6, r.moved_mean / 1e6, r.moved_mean / r.bound, r.message_bytes_per_pixel);
  }
  for (const Row& r : rows) {
    if (r.model) continue;
    std::printf("image hash P=%d size=%d %s %s %s: %016" PRIx64 "\n", r.ranks, r.size,
                r.coverage.c_str(), r.algorithm.c_str(), r.rows.c_str(), r.root_image_hash);
  }
}

std::string hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, value);
  return text;
}

bool write_json(const std::string& path, const std::vector<Row>& rows, const MachineCosts& c,
                const std::vector<FragmentRow>& fragments) {
  using bench::number;
  Json::Value json;
  json["latency_us"] = number(c.latency_s * 1e6);
  json["bandwidth_GBps"] = number(c.bandwidth_Bps / 1e9);
  json["scan_ns_per_pixel"] = number(c.pixel.scan * 1e9);
  json["encode_ns_per_pixel"] = number(c.pixel.encode * 1e9);
  json["composite_ns_per_pixel"] = number(c.pixel.composite * 1e9);
  json["copy_ns_per_pixel"] = number(c.pixel.copy * 1e9);
  json["runs"] = Json::Value(Json::arrayValue);
  for (const Row& r : rows) {
    Json::Value run;
    run["ranks"] = r.ranks;
    run["size"] = r.size;
    run["mode"] = r.coverage;
    run["algorithm"] = r.algorithm;
    run["rows"] = r.rows;
    run["image"] = r.model ? "model" : "real";
    run["rounds"] = r.rounds;
    run["median_ms"] = number(r.median_ms);
    run["min_ms"] = number(r.min_ms);
    run["composite_ms"] = number(r.composite_ms);
    run["assembly_ms"] = number(r.assembly_ms);
    run["round_end_ms"] = Json::Value(Json::arrayValue);
    for (double t : r.round_end_ms) run["round_end_ms"].append(number(t));
    run["sent_max_bytes"] = number(r.sent_max);
    run["moved_mean_bytes"] = number(r.moved_mean);
    run["moved_max_bytes"] = number(r.moved_max);
    run["bound_bytes"] = number(r.bound);
    run["message_bytes_per_pixel"] = number(r.message_bytes_per_pixel);
    if (!r.model) run["root_image_hash"] = hex(r.root_image_hash);
    json["runs"].append(run);
  }
  json["fragments"] = Json::Value(Json::arrayValue);
  for (const FragmentRow& r : fragments) {
    Json::Value row;
    row["ranks"] = r.ranks;
    row["size"] = r.size;
    row["mode"] = r.coverage;
    row["opaque_ms"] = number(r.opaque_ms);
    row["fragments_ms"] = number(r.fragments_ms);
    row["fragments_per_rank"] = number(r.fragments_per_rank);
    row["ratio"] = number(r.ratio());
    row["target_ratio"] = number(kFragmentTargetRatio);
    row["target_met"] = r.ratio() <= kFragmentTargetRatio;
    json["fragments"].append(row);
  }
  return bench::write_json_file(json, path);
}

}  // namespace tetray::composite_bench
