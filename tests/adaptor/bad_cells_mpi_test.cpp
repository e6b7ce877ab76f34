// One rank's bad cells or values, run under mpirun on 2 and 3 ranks (and a ctest timeout, so a
// hang fails): whichever rank holds them, every rank returns the same status code and message,
// naming that rank and the fault as the input checks word it (adaptor/input/cell_split.cpp,
// render/volume/mesh_check.cpp), and the next step, good on every rank and saying only what the
// solver changed to repair it, renders the image of a run that never failed, byte for byte.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "rank_cells.hpp"
#include "same_status.hpp"
#include "shared_dir.hpp"
#include "support/cell_meshes.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kCubes = 6, kSide = 48;
constexpr double kRadius = 0.6;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string config(const std::string& directory) {
  return ball_config(directory, kRadius, "[0.4, 0.3, 3]", 40, kSide);
}

// The point of `cells` whose distance to the centre is nearest the isovalue: a fault there
// changes the surface if anything does.
std::size_t point_near_the_surface(const RankCells& cells) {
  std::size_t best = 0;
  for (std::size_t p = 1; p < cells.distance.size(); ++p) {
    if (std::abs(cells.distance[p] - kRadius) < std::abs(cells.distance[best] - kRadius)) best = p;
  }
  return best;
}

std::string cell_text(int cell, int type) {
  return "mesh.cells: cell " + std::to_string(cell) + " (VTK cell type " + std::to_string(type) +
         ")";
}

// A fault a solver's arrays can have: `spoil` puts it into one rank's share and returns the
// beginning of the message that rank's checks must give; the solver then repairs its arrays
// and says that `repair` changed.
struct Fault {
  const char* name;
  StatusCode code;
  std::string (*spoil)(RankCells& cells);
  Changes repair;
};

constexpr Changes kTopology{true, true, true};
constexpr Changes kGeometryOnly{true, false, false};
constexpr Changes kFieldsOnly{false, false, true};

const Fault kFaults[] = {
    {"a cell naming a point past the last", StatusCode::invalid_argument,
     [](RankCells& c) {
       const auto points = static_cast<std::int64_t>(c.distance.size());
       c.connectivity[static_cast<std::size_t>(c.offsets[1]) + 2] = points;
       return cell_text(1, 12) + " names point " + std::to_string(points) + " outside [0, " +
              std::to_string(points) + ")";
     },
     kTopology},
    {"a cell naming a negative point", StatusCode::invalid_argument,
     [](RankCells& c) {
       c.connectivity[5] = -1;
       return cell_text(0, 12) + " names point -1 outside [0, " +
              std::to_string(c.distance.size()) + ")";
     },
     kTopology},
    {"an unknown cell type", StatusCode::invalid_argument,
     [](RankCells& c) {
       c.types[2] = 99;
       return cell_text(2, 99) + " is not a cell tetray renders";
     },
     kTopology},
    {"a cell type with another node count", StatusCode::invalid_argument,
     [](RankCells& c) {
       c.types[0] = 14;  // a pyramid's 5 nodes, given a hexahedron's 8
       return cell_text(0, 14) + " has 8 nodes, not 5";
     },
     kTopology},
    {"offsets running backwards", StatusCode::invalid_argument,
     [](RankCells& c) {
       c.offsets[2] = c.offsets[1] - 1;
       return "mesh.cells: the cell offsets of cell 1 run outside the " +
              std::to_string(c.connectivity.size()) + " connectivity entries";
     },
     kTopology},
    {"a NaN coordinate", StatusCode::invalid_argument,
     [](RankCells& c) {
       const std::size_t p = point_near_the_surface(c);
       c.xyz[3 * p + 1] = kNaN;
       return "mesh with field 'distance': non-finite coordinate nan at point " +
              std::to_string(p) + " (1 such point)";
     },
     kGeometryOnly},
    // The cells are split, and tie keys made, from the points' positions at a new topology:
    // those of this failed step must not outlive it.
    {"coordinates never filled (all NaN)", StatusCode::invalid_argument,
     [](RankCells& c) {
       std::fill(c.xyz.begin(), c.xyz.end(), kNaN);
       return "mesh with field 'distance': non-finite coordinate nan at point 0 (" +
              std::to_string(c.distance.size()) + " such points)";
     },
     kGeometryOnly},
    {"an infinite coordinate", StatusCode::invalid_argument,
     [](RankCells& c) {
       const std::size_t p = point_near_the_surface(c);
       c.xyz[3 * p] = -kInf;
       return "mesh with field 'distance': non-finite coordinate -inf at point " +
              std::to_string(p) + " (1 such point)";
     },
     kGeometryOnly},
    {"a non-finite field value", StatusCode::partial,
     [](RankCells& c) {
       const std::size_t p = point_near_the_surface(c);
       c.distance[p] = kNaN;
       return "scene 'ball' skipped: mesh with field 'distance': non-finite field value nan at "
              "point " +
              std::to_string(p) + " (1 such point)";
     },
     kFieldsOnly},
};

// The expected message, with "rank N: " where the agreement puts it: before the whole message,
// or, for a skipped scene, before the skip's reason.
std::string naming_the_rank(const std::string& message, int faulty) {
  const std::string skip = "scene 'ball' skipped: ";
  if (message.rfind(skip, 0) == 0) return skip + rank_prefix(faulty) + message.substr(skip.size());
  return rank_prefix(faulty) + message;
}

// `text` as rank `root` has it, on every rank.
std::string from_rank(std::string text, int root) {
  auto length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, root, MPI_COMM_WORLD);
  text.resize(static_cast<std::size_t>(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, root, MPI_COMM_WORLD);
  return text;
}

class BadCells : public ::testing::Test {
 protected:
  void SetUp() override {
    const CellMesh mesh = lattice(kCubes, hexahedra);
    const std::size_t cells = mesh.types.size();
    const auto bound = [&](int r) { return cells * static_cast<std::size_t>(r) / world_size(); };
    good_ = share(mesh, bound(rank()), bound(rank() + 1), 29 + rank());
    Status status;
    adaptor_ = Adaptor::create_from_yaml(MPI_COMM_WORLD, config(shared_.path()), status);
    ASSERT_TRUE(adaptor_) << status.message;
  }

  std::string image(std::int64_t step) const {
    char name[64];
    std::snprintf(name, sizeof name, "ball/ball_%06lld.png", static_cast<long long>(step));
    return (fs::path(shared_.path()) / name).string();
  }

  // Step `step` with `cells` here; the status of every rank is checked to be the same.
  Status run(std::int64_t step, const RankCells& cells, const Changes& changes = {}) {
    const Status status =
        adaptor_->execute(step, static_cast<double>(step), cells.view(), cells.fields(), changes);
    expect_same_on_every_rank(status);
    return status;
  }

  // The fault on `faulty` fails step `step` on every rank alike; step + 1, repaired, renders.
  void expect_fault_then_recovery(const Fault& fault, int faulty, std::int64_t step) {
    RankCells spoiled = good_;
    // The faulty rank's points are its own: the message it expects is the one to check.
    const std::string expected = from_rank(naming_the_rank(fault.spoil(spoiled), faulty), faulty);
    const Status failed = run(step, rank() == faulty ? spoiled : good_);
    EXPECT_EQ(failed.code, fault.code)
        << fault.name << " on rank " << faulty << ": " << failed.message;
    EXPECT_EQ(failed.message.substr(0, expected.size()), expected) << fault.name;
    const Status repaired = run(step + 1, good_, fault.repair);
    EXPECT_TRUE(repaired.ok()) << fault.name << " on rank " << faulty
                               << ", repaired: " << repaired.message;
  }

  const SharedDir shared_{"bad_cells"};
  RankCells good_;
  std::unique_ptr<Adaptor> adaptor_;
};

// Every rank goes through every step whatever it finds, so that none is left waiting.
TEST_F(BadCells, OnAnyOneRankEveryRankGetsItsErrorAndTheRepairedStepRendersAsEver) {
  ASSERT_TRUE(run(0, good_).ok());
  struct Case {
    const Fault* fault;
    int faulty;
  };
  std::vector<Case> cases;  // case k fails step 2k + 1, repaired at step 2k + 2
  for (const Fault& fault : kFaults) {
    for (int faulty = 0; faulty < world_size(); ++faulty) cases.push_back({&fault, faulty});
  }
  for (std::size_t k = 0; k < cases.size(); ++k) {
    expect_fault_then_recovery(*cases[k].fault, cases[k].faulty,
                               static_cast<std::int64_t>(2 * k + 1));
  }
  ASSERT_TRUE(adaptor_->finalize().ok());
  if (rank() != 0) return;
  const std::string reference = slurp(image(0));
  ASSERT_FALSE(reference.empty());
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto step = static_cast<std::int64_t>(2 * k + 1);
    const std::string what =
        std::string(cases[k].fault->name) + " on rank " + std::to_string(cases[k].faulty);
    EXPECT_FALSE(fs::exists(image(step))) << what;
    // Not EXPECT_EQ: the PNG's bytes would fill the report.
    EXPECT_TRUE(slurp(image(step + 1)) == reference) << "repaired after " << what;
  }
}

// Two ranks at fault at once, each its own way: every rank gets the lowest one's message.
TEST_F(BadCells, TwoFaultyRanksGiveEveryRankTheLowestOnesMessage) {
  const int low = world_size() - 2, high = world_size() - 1;
  RankCells spoiled = good_;
  const std::string low_message = rank() == low ? kFaults[2].spoil(spoiled) : "";
  if (rank() == high) kFaults[0].spoil(spoiled);
  const Status failed = run(0, rank() == low || rank() == high ? spoiled : good_);
  EXPECT_EQ(failed.code, StatusCode::invalid_argument);
  const std::string expected = from_rank(rank_prefix(low) + low_message, low);
  EXPECT_EQ(failed.message.substr(0, expected.size()), expected);
  EXPECT_TRUE(run(1, good_).ok());
  EXPECT_TRUE(adaptor_->finalize().ok());
}

}  // namespace
}  // namespace tetray::testing
