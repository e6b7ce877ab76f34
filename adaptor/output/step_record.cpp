#include "adaptor/output/step_record.hpp"

#include <cstdio>

namespace tetray {
namespace {

std::string ms(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::string time_text(double time) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", time);
  return buf;
}

std::string log_header() {
  return "step,time,scene,check_ms,ingest_ms,bvh_ms,bvh_update,color_ms,trace_ms,composite_ms,"
         "agree_ms,probes_ms,hand_off_ms,queue_wait_ms,other_ms,blocked_ms,encode_ms,write_ms,tets,"
         "kept_tets,skipped_tets,rays,hits,bvh_bytes,"
         "peak_rss_bytes,threads";
}

std::string log_row(const StepRecord& r) {
  return std::to_string(r.step) + ',' + time_text(r.time) + ',' + r.scene + ',' + ms(r.check_ms) +
         ',' + ms(r.ingest_ms) + ',' + ms(r.bvh_ms) + ',' + r.bvh_update + ',' + ms(r.color_ms) +
         ',' + ms(r.trace_ms) + ',' + ms(r.composite_ms) + ',' + ms(r.agree_ms) + ',' +
         ms(r.probes_ms) + ',' + ms(r.hand_off_ms) + ',' + ms(r.queue_wait_ms) + ',' +
         ms(r.other_ms) + ',' + ms(r.blocked_ms) + ',' + ms(r.encode_ms) + ',' + ms(r.write_ms) +
         ',' + std::to_string(r.tets) + ',' + std::to_string(r.kept_tets) + ',' +
         std::to_string(r.skipped_tets) + ',' + std::to_string(r.rays) + ',' +
         std::to_string(r.hits) + ',' + std::to_string(r.bvh_bytes) + ',' +
         std::to_string(r.peak_rss_bytes) + ',' + std::to_string(r.threads);
}

}  // namespace tetray
