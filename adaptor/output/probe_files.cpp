#include "adaptor/output/probe_files.hpp"

#include <cstdio>

#include "adaptor/output/line_file.hpp"
#include "adaptor/output/step_record.hpp"

namespace tetray {
namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string rows(const config::ProbeSet& set, std::int64_t step, double time,
                 const std::vector<std::uint8_t>& held, const std::vector<double>& values) {
  std::string text;
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    if (i > 0) text += '\n';
    const render::Vec3d& p = set.points[i];
    text += std::to_string(step) + ',' + time_text(time) + ',' + std::to_string(i) + ',' +
            number_text(p.x) + ',' + number_text(p.y) + ',' + number_text(p.z);
    for (std::size_t f = 0; f < set.fields.size(); ++f) {
      text += ',';
      text += held[i] ? number_text(values[i * set.fields.size() + f]) : "outside";
    }
  }
  return text;
}

}  // namespace

std::string probe_path(const std::string& directory, const std::string& set_name) {
  return directory + "/probe_" + set_name + ".csv";
}

std::string write_probe_headers(const std::string& directory,
                                const std::vector<config::ProbeSet>& sets) {
  for (const config::ProbeSet& set : sets) {
    std::string header = "step,time,point,x,y,z";
    for (const std::string& f : set.fields) header += ',' + f;
    if (std::string e = replace_lines(probe_path(directory, set.name), {header}); !e.empty()) {
      return e;
    }
  }
  return {};
}

std::string append_probe_rows(const std::string& directory, const config::ProbeSet& set,
                              std::int64_t step, double time, const std::vector<std::uint8_t>& held,
                              const std::vector<double>& values) {
  return append_line(probe_path(directory, set.name), rows(set, step, time, held, values));
}

}  // namespace tetray
