// The compositor against the brute-force reference (gather everything, nearest per pixel, ties
// to the smaller key, spelled apart from the library's wins_over), for every algorithm, at
// whatever rank count mpirun gives (ctest runs 1, 2, 3, 4, 5, 8 and 16), each in both row orders
// of the schedule (CompositeRows).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "composite_test_images.hpp"
#include "render/composite/composite.hpp"
#include "render/composite/composite_codec.hpp"
#include "render/composite/composite_plan.hpp"
#include "render/composite/composite_region.hpp"

namespace tetray::render {
namespace {

using testing::brute_force_composite;
using testing::Coverage;
using testing::random_coverage;
using testing::random_image;
using testing::World;
using testing::world;

constexpr std::uint64_t kHeaderBytes = kPieceHeaderWords * sizeof(std::uint32_t);
constexpr std::uint64_t kRunBytes = kRunHeaderWords * sizeof(std::uint32_t);
constexpr std::uint64_t kPixelBytes = kPixelWords * sizeof(std::uint32_t);

std::size_t count_differences(const Framebuffer& a, const Framebuffer& b) {
  std::size_t differences = 0;
  for (std::size_t p = 0; p < a.pixel_count(); ++p) {
    bool same = a.depth[p] == b.depth[p] && a.hit[p] == b.hit[p];
    for (int c = 0; c < 4; ++c) same = same && a.rgba[4 * p + c] == b.rgba[4 * p + c];
    differences += same ? 0 : 1;
  }
  return differences;
}

// Messages a rank sends at most: one per other group member per round, and one piece in the
// assembly.
std::uint64_t max_messages_sent(const CompositePlan& plan) {
  return std::accumulate(plan.radices.begin(), plan.radices.end(), std::uint64_t{1},
                         [](std::uint64_t sum, int k) { return sum + k - 1; });
}

// Pixels rank `v` (root 0) sends under `plan`, every pixel active, derived from the schedule's
// definition: a folded rank its whole image; a gathering rank too; otherwise the parts it gives
// away in the radix rounds, then in the assembly, which takes the rounds back in reverse, the
// span it holds when its digit is first non-zero.
std::uint64_t pixels_sent(const CompositePlan& plan, int v, std::size_t image_pixels) {
  PixelSpan span{0, static_cast<std::uint32_t>(image_pixels)};
  if (v >= plan.swap_count || (plan.radices.empty() && v != 0)) return span.size();
  std::uint64_t sent = 0;
  std::vector<PixelSpan> held_after_round;
  for (std::size_t round = 0; round < plan.radices.size(); ++round) {
    const int digit = round_position(plan, static_cast<int>(round), v).digit;
    for (int part = 0; part < plan.radices[round]; ++part) {
      if (part != digit) sent += split_span(span, plan.radices[round], part).size();
    }
    span = split_span(span, plan.radices[round], digit);
    held_after_round.push_back(span);
  }
  for (auto round = static_cast<int>(plan.radices.size()) - 1; round >= 0; --round) {
    if (round_position(plan, round, v).digit != 0) {
      return sent + held_after_round[static_cast<std::size_t>(round)].size();
    }
  }
  return sent;
}

class CompositeMpi
    : public ::testing::TestWithParam<std::tuple<CompositeAlgorithm, CompositeRows>> {
 protected:
  static CompositeAlgorithm algorithm() { return std::get<0>(GetParam()); }
  static bool interlaced() { return std::get<1>(GetParam()) == CompositeRows::interlaced; }
  static CompositeOptions options(int root, std::optional<PixelRect> hint = {}) {
    return {algorithm(), root, hint, std::get<1>(GetParam())};
  }

  // Composites `image` on `root` and checks it against the reference there.
  CompositeStats composite_and_check(Framebuffer image, int root, const std::string& what) {
    const Framebuffer expected = brute_force_composite(image, MPI_COMM_WORLD, root);
    CompositeStats stats;
    EXPECT_EQ(composite(image, MPI_COMM_WORLD, options(root), &stats), MPI_SUCCESS) << what;
    EXPECT_EQ(stats.interlaced, interlaced() && world().size > 1) << what;
    if (world().rank == root) {
      EXPECT_EQ(count_differences(image, expected), 0u) << what;
    }
    return stats;
  }
};

TEST_P(CompositeMpi, MatchesBruteForceOnRandomImages) {
  const World w = world();
  const int sizes[][2] = {{64, 48}, {257, 131}};
  for (const auto& size : sizes) {
    for (std::uint32_t seed = 0; seed < 4; ++seed) {
      const Framebuffer image =
          random_image(size[0], size[1], seed, w.rank, w.size, random_coverage(seed, w.rank));
      composite_and_check(image, static_cast<int>(seed) % w.size,
                          std::to_string(size[0]) + "x" + std::to_string(size[1]) + " seed " +
                              std::to_string(seed));
    }
  }
}

TEST_P(CompositeMpi, AllRanksEmptyGiveTheBackground) {
  const World w = world();
  Framebuffer image(64, 48);
  CompositeStats stats;
  EXPECT_EQ(composite(image, MPI_COMM_WORLD, options(0), &stats), MPI_SUCCESS);
  if (w.rank == 0) {
    EXPECT_EQ(count_differences(image, Framebuffer(64, 48)), 0u);
  }
  // Empty pieces cost their headers only.
  EXPECT_EQ(stats.bytes_sent % kHeaderBytes, 0u);
  EXPECT_LE(stats.bytes_sent, kHeaderBytes * max_messages_sent(make_plan(w.size, algorithm())));
}

TEST_P(CompositeMpi, AHintHoldingTheActivePixelsGivesTheSameImageAndBytes) {
  const World w = world();
  const Framebuffer image = random_image(257, 131, 5, w.rank, w.size, random_coverage(5, w.rank));
  const Framebuffer expected = brute_force_composite(image, MPI_COMM_WORLD, 0);
  CompositeStats plain_stats, hinted_stats;
  Framebuffer plain = image, hinted = image;
  // A loose hint (the active rectangle grown by 3 pixels, as the adaptor's screen bound is),
  // and for an empty rank an empty one.
  PixelRect hint = active_rect(image);
  if (!hint.empty()) hint = {hint.x0 - 3, hint.y0 - 3, hint.x1 + 3, hint.y1 + 3};
  ASSERT_EQ(composite(plain, MPI_COMM_WORLD, options(0), &plain_stats), MPI_SUCCESS);
  ASSERT_EQ(composite(hinted, MPI_COMM_WORLD, options(0, hint), &hinted_stats), MPI_SUCCESS);
  if (w.rank == 0) {
    EXPECT_EQ(count_differences(hinted, expected), 0u);
  }
  EXPECT_EQ(hinted_stats.bytes_sent, plain_stats.bytes_sent);
}

TEST_P(CompositeMpi, OneEmptyRankAmongFullOnes) {
  const World w = world();
  for (int empty_rank = 0; empty_rank < w.size; empty_rank += 2) {
    const Coverage coverage = w.rank == empty_rank ? Coverage::empty : Coverage::full;
    composite_and_check(random_image(257, 131, 11, w.rank, w.size, coverage), 0,
                        "empty rank " + std::to_string(empty_rank));
  }
}

TEST_P(CompositeMpi, VeryUnequalWork) {
  // One rank covers the whole screen; every other rank hits a single pixel.
  const World w = world();
  const int busy_rank = w.size - 1;
  Framebuffer image = random_image(257, 131, 5, w.rank, w.size,
                                   w.rank == busy_rank ? Coverage::full : Coverage::empty);
  if (w.rank != busy_rank) {
    const std::size_t p = image.index(17 * w.rank % 257, 13 * w.rank % 131);
    image.depth[p] = 0.5f;
    image.hit[p] = static_cast<std::uint32_t>(w.rank);
    image.rgba[4 * p] = 1.0f;
  }
  composite_and_check(image, 0, "unequal work");
}

// Every rank covers whole rows, without holes, of a band of the image (another band per rank,
// overlapping): the assembly's pieces are then single runs that start or end inside their span,
// which must not be taken as a whole span in place, beside whole spans that are.
TEST_P(CompositeMpi, BandsOfWholeRowsMatchBruteForce) {
  const World w = world();
  constexpr int kWidth = 61, kHeight = 47;
  Framebuffer image(kWidth, kHeight);
  const int y0 = (7 * w.rank) % kHeight, y1 = std::min(kHeight, y0 + 5 + 11 * (w.rank % 3));
  for (int j = y0; j < y1; ++j) {
    for (int i = 0; i < kWidth; ++i) {
      const std::size_t p = image.index(i, j);
      image.depth[p] = 1.0f + 0.25f * static_cast<float>((i + j + w.rank) % 5);
      image.hit[p] = static_cast<std::uint32_t>(p) * static_cast<std::uint32_t>(w.size) +
                     static_cast<std::uint32_t>(w.rank);
      for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = 0.1f * static_cast<float>(c + w.rank);
    }
  }
  for (int root = 0; root < std::min(w.size, 2); ++root)
    composite_and_check(image, root, "bands, root " + std::to_string(root));
}

TEST_P(CompositeMpi, DenseImagesSendWhatTheScheduleSays) {
  const World w = world();
  const Framebuffer image = random_image(257, 131, 3, w.rank, w.size, Coverage::full);
  const CompositeStats stats = composite_and_check(image, 0, "dense");
  const CompositePlan plan = make_plan(w.size, algorithm());
  const std::uint64_t pixels = pixels_sent(plan, w.rank, image.pixel_count());
  const std::uint64_t messages = max_messages_sent(plan);
  // A piece is one run in natural order; interlaced, one run per row it reaches.
  const std::uint64_t runs = interlaced() ? static_cast<std::uint64_t>(image.height) + 1 : 1;
  EXPECT_GE(stats.bytes_sent, pixels * kPixelBytes + (w.rank != 0 ? kHeaderBytes + kRunBytes : 0));
  EXPECT_LE(stats.bytes_sent, pixels * kPixelBytes + messages * (kHeaderBytes + runs * kRunBytes));
  // The root's peak holds at least the largest piece it receives: the other half of the image
  // in the last assembly step of binary swap.
  EXPECT_GE(stats.peak_message_bytes, w.rank == 0 && w.size > 1 ? kPixelBytes : 0);
  std::uint64_t totals[] = {stats.bytes_sent, stats.bytes_received};
  MPI_Allreduce(MPI_IN_PLACE, totals, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(totals[0], totals[1]);
}

TEST_P(CompositeMpi, ReportsTheRoundsOfItsPlan) {
  const World w = world();
  Framebuffer image = random_image(64, 48, 1, w.rank, w.size, Coverage::full);
  CompositeStats stats;
  ASSERT_EQ(composite(image, MPI_COMM_WORLD, options(0), &stats), MPI_SUCCESS);
  EXPECT_EQ(stats.rounds, w.size == 1 ? 0 : make_plan(w.size, algorithm()).round_count());
  EXPECT_GE(stats.seconds, 0.0);
}

std::string schedule_name(
    const ::testing::TestParamInfo<std::tuple<CompositeAlgorithm, CompositeRows>>& info) {
  constexpr const char* kAlgorithms[] = {"automatic", "binary_swap", "radix_k", "gather"};
  constexpr const char* kRows[] = {"automatic", "natural", "interlaced"};
  return std::string(kAlgorithms[static_cast<int>(std::get<0>(info.param))]) + "_" +
         kRows[static_cast<int>(std::get<1>(info.param))];
}

INSTANTIATE_TEST_SUITE_P(
    Schedules, CompositeMpi,
    ::testing::Combine(::testing::Values(CompositeAlgorithm::automatic,
                                         CompositeAlgorithm::binary_swap,
                                         CompositeAlgorithm::radix_k, CompositeAlgorithm::gather),
                       ::testing::Values(CompositeRows::natural, CompositeRows::interlaced)),
    schedule_name);

// CompositeRows::automatic: interlaced when every rank's active rows span at most a quarter of
// the image's height, natural as soon as one rank's span more; the same image either way.
TEST(CompositeRowsAutomatic, InterlacesWhenEveryRankCoversAShortBand) {
  const World w = world();
  constexpr int kWidth = 40, kHeight = 64;
  for (const int tallest : {kHeight / 4, kHeight / 4 + 1}) {
    Framebuffer image(kWidth, kHeight);
    // Rank r's band starts at row 3 r; the last rank's is `tallest` rows, the others' 5.
    const int y0 = (3 * w.rank) % (kHeight - tallest);
    const int rows = w.rank == w.size - 1 ? tallest : 5;
    for (int j = y0; j < y0 + rows; ++j) {
      for (int i = w.rank % 7; i < kWidth; i += 2) {
        const std::size_t p = image.index(i, j);
        image.depth[p] = 1.0f + 0.125f * static_cast<float>((i * 3 + j + w.rank) % 11);
        image.hit[p] = static_cast<std::uint32_t>(p * 64 + static_cast<std::size_t>(w.rank));
        for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = 0.05f * static_cast<float>(c + j);
      }
    }
    const Framebuffer expected = brute_force_composite(image, MPI_COMM_WORLD, 0);
    CompositeStats stats;
    ASSERT_EQ(composite(image, MPI_COMM_WORLD, {}, &stats), MPI_SUCCESS);
    EXPECT_EQ(stats.interlaced, w.size > 1 && tallest <= kHeight / 4) << "tallest " << tallest;
    if (w.rank == 0) {
      EXPECT_EQ(count_differences(image, expected), 0u) << "tallest " << tallest;
    }
  }
}

// Ranks that ask for different row orders are refused on every rank, as different algorithms.
TEST(CompositeErrorsOnTwoRanks, DifferentRowOrdersFailOnEveryRank) {
  const World w = world();
  ASSERT_GE(w.size, 2) << "needs two ranks";
  Framebuffer image = random_image(32, 16, 1, w.rank, w.size, Coverage::full);
  CompositeOptions options;
  options.rows = w.rank == 0 ? CompositeRows::interlaced : CompositeRows::natural;
  EXPECT_EQ(composite(image, MPI_COMM_WORLD, options), MPI_ERR_ARG);
}

// A piece sent from the image in place (its active pixels one run) and one sent as copied words
// arrive, through MPI, as the words the encoder writes for the same span; only the one-run piece
// goes in place, and interlaced one that holds every pixel of its span (a run per row, each
// another image row's). On each rank, to itself.
TEST(OutgoingPiece, ArrivesAsTheEncodedWordsInPlaceOrCopied) {
  Framebuffer image(37, 40);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    image.rgba[4 * p] = 0.25f * static_cast<float>(p % 7);
    image.rgba[4 * p + 3] = 1.0f;
    image.depth[p] = 1.0f + static_cast<float>(p);
    image.hit[p] = static_cast<std::uint32_t>(3 * p);
  }
  Framebuffer holes = image;  // the same with a background pixel in every row: a run per row
  for (int j = 0; j < holes.height; ++j) {
    holes.depth[holes.index(5, j)] = std::numeric_limits<float>::infinity();
    holes.hit[holes.index(5, j)] = kNoHit;
  }
  const std::vector<std::uint32_t> rows = interlaced_rows(image.height);
  const PixelSpan across_rows{30, 1300}, in_row{40, 70};
  struct Case {
    const Framebuffer* source;
    PixelSpan span;
    RowOrder order;
    bool in_place;
  };
  const Case cases[] = {{&image, across_rows, {}, true},     {&holes, across_rows, {}, false},
                        {&image, across_rows, {rows}, true}, {&holes, across_rows, {rows}, false},
                        {&image, in_row, {rows}, true},      {&holes, in_row, {rows}, false}};
  for (const Case& c : cases) {
    const Framebuffer* source = c.source;
    OutgoingPiece piece = outgoing_piece(*source, c.span, active_rect(*source), c.order);
    EXPECT_EQ(piece.in_place(), c.in_place);
    const PieceMessage expected = encode_piece(*source, c.span, active_rect(*source), c.order);
    EXPECT_EQ(message_bytes(piece), expected.size() * sizeof(std::uint32_t));
    std::vector<std::uint32_t> received(expected.size() + 8, 0xdeadbeef);
    MPI_Request requests[2];
    ASSERT_EQ(MPI_Irecv(received.data(), static_cast<int>(received.size()), MPI_UINT32_T, 0, 5,
                        MPI_COMM_SELF, &requests[0]),
              MPI_SUCCESS);
    ASSERT_EQ(isend_piece(piece, 0, 5, MPI_COMM_SELF, &requests[1]), MPI_SUCCESS);
    MPI_Status statuses[2];
    ASSERT_EQ(MPI_Waitall(2, requests, statuses), MPI_SUCCESS);
    int count = 0;
    MPI_Get_count(&statuses[0], MPI_UINT32_T, &count);
    ASSERT_EQ(static_cast<std::size_t>(count), expected.size());
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), received.begin()));
    const PieceMessage wire = piece.wire();
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), wire.begin(), wire.end()));
  }
}

TEST(CompositeOneRank, ReturnsAtOnceWithoutCopies) {
  Framebuffer image = random_image(64, 48, 2, 0, 1, Coverage::random_rect);
  const Framebuffer before = image;
  const float* rgba = image.rgba.data();
  CompositeStats stats;
  stats.rounds = 99;
  EXPECT_EQ(composite(image, MPI_COMM_SELF, {}, &stats), MPI_SUCCESS);
  EXPECT_EQ(image.rgba.data(), rgba);
  EXPECT_EQ(count_differences(image, before), 0u);
  EXPECT_EQ(stats.rounds, 0);
  EXPECT_EQ(stats.bytes_sent + stats.bytes_received, 0u);
}

// On one rank every image has the same size: ctest leaves the suite out there.
TEST(CompositeErrorsOnTwoRanks, DifferentImageSizesFailOnEveryRank) {
  const World w = world();
  ASSERT_GE(w.size, 2) << "needs two ranks";
  Framebuffer image(64, w.rank == 0 ? 48 : 47);
  EXPECT_EQ(composite(image, MPI_COMM_WORLD, {}), MPI_ERR_ARG);
}

TEST(CompositeErrors, MalformedImageFailsOnEveryRank) {
  const World w = world();
  Framebuffer image(64, 48);
  if (w.rank == w.size - 1) image.hit.pop_back();
  const int expected = w.size == 1 ? MPI_SUCCESS : MPI_ERR_ARG;
  EXPECT_EQ(composite(image, MPI_COMM_WORLD, {}), expected);
}

TEST(CompositeErrors, RootOutOfRangeFailsOnEveryRank) {
  const World w = world();
  Framebuffer image(16, 16);
  CompositeOptions options;
  options.root = w.size;
  EXPECT_EQ(composite(image, MPI_COMM_WORLD, options), MPI_ERR_ROOT);
}

}  // namespace
}  // namespace tetray::render
