// Answers that several ranks may hold (a probe point on a face between sub-domains, in two
// ranks' tets), taken from exactly one: the lowest rank holding each item. The same items on
// any number of ranks give the same answers, and no answer is counted twice.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace tetray::render {

// `held[i]` says whether this rank holds item i, `values[i * width, (i + 1) * width)` its answer.
// On `root`, held[i] becomes whether any rank holds item i and the values are the lowest such
// rank's (zero where none does). Collective; returns MPI_SUCCESS or the MPI error code.
int gather_from_lowest_holder(std::span<std::uint8_t> held, std::span<double> values,
                              std::size_t width, int root, MPI_Comm comm);

}  // namespace tetray::render
