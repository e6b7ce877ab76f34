// Probes (docs/architecture.md §8): at every rendered step each probe point is located in a tet
// of this rank's volume (render/walk/point_locate.hpp), its fields interpolated barycentrically
// from the solver's own arrays in double precision, and the answers of exactly one rank per point
// (the lowest rank whose tets contain it, render/parallel/owner_reduce.hpp) gathered on the
// writer rank, which appends one row per point to the set's CSV file
// (adaptor/output/probe_files.hpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "adaptor/config/config.hpp"
#include "adaptor/step/collective.hpp"
#include "adaptor/step/field_volume.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

class ProbeSampler {
 public:
  explicit ProbeSampler(std::vector<config::ProbeSet> sets) : sets_(std::move(sets)) {}

  bool empty() const { return sets_.empty(); }

  // On the writer rank before the first step: every set's CSV, new, with its header.
  std::string prepare(const std::string& directory) const;

  // Collective over `comm`: samples every set in `volume` (null or empty: this rank holds no
  // point) and appends the rows on `root`. Returns this rank's error, empty on success; a rank
  // that fails to sample still joins the collective, holding no point.
  std::string sample(const Communicator& comm, int root, const FieldVolume* volume,
                     std::span<const FieldView> fields, std::int64_t step, double time,
                     const std::string& directory) const;

 private:
  std::vector<config::ProbeSet> sets_;
};

}  // namespace tetray
