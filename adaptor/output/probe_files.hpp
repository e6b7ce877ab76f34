// The probes' CSV files (docs/architecture.md §8): `<directory>/probe_<name>.csv`, created with
// the header `step,time,point,x,y,z,<field>...`, then one row per point at every rendered step,
// with `outside` for a point no rank's tets contain. Written on the writer rank only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "adaptor/config/config.hpp"

namespace tetray {

std::string probe_path(const std::string& directory, const std::string& set_name);

// Every set's file, new, with its header. Returns an error, empty on success.
std::string write_probe_headers(const std::string& directory,
                                const std::vector<config::ProbeSet>& sets);

// Appends one row per point of `set`: held[i] says whether some rank's tets contain point i,
// values[i * set.fields.size() + f] is then its field f. Returns an error, empty on success.
std::string append_probe_rows(const std::string& directory, const config::ProbeSet& set,
                              std::int64_t step, double time, const std::vector<std::uint8_t>& held,
                              const std::vector<double>& values);

}  // namespace tetray
