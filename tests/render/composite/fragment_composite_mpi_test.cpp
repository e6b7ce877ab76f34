// Fragment compositing across ranks: the gyroid-twist field volume-rendered by every rank on its
// own tets (slabs, and a random partition whose sub-domains are full of holes, so pixels get many
// fragments per rank) and composited on rank 0 gives the image of one rank rendering all tets
// bit for bit: the over operator is not associative, so partition-dependent fragment boundaries
// change the double sums by about 1e-16 relative, which the float image does not see
// (render/core/fragments.hpp, docs/architecture.md §8). The merge of one pixel against
// hand-worked orders and colors is tests/render/composite/fragment_merge_test.cpp.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <new>
#include <random>
#include <span>
#include <stdexcept>
#include <tuple>

#include "composite_test_images.hpp"
#include "render/composite/fragment_composite.hpp"
#include "render/walk/volume_render.hpp"
#include "support/render_fixtures.hpp"

namespace tetray::render {
namespace {

using testing::world;

const GyroidTwist& scene() {
  static const GyroidTwist gyroid = make_gyroid_twist(10, 0.2);
  return gyroid;
}

const Colormap& colormap() { return *find_colormap("coolwarm"); }

VolumeRenderOptions options(double termination = 1, double unit_distance = 0.5) {
  VolumeRenderOptions o;
  o.transfer = {
      &colormap(), -1.5, 1.5, {{-1.5, 0.0}, {-0.5, 0.3}, {0.2, 0.0}, {1.0, 2.0}}, unit_distance};
  o.termination = termination;
  return o;
}

// The fragments of the tets `owner` gives to `rank`, all points passed (the store keeps the
// used ones), vertices relative to the centre of the whole mesh's points.
VolumeFragmentImage render_piece(const std::function<int(std::size_t)>& owner, int rank,
                                 double termination = 1, double unit_distance = 0.5,
                                 VolumeRenderStats* stats = nullptr) {
  const GyroidTwist& g = scene();
  std::vector<std::int64_t> tets;
  std::vector<std::uint32_t> ids;
  for (std::size_t t = 0; t < g.mesh.tet_count(); ++t) {
    if (owner(t) != rank) continue;
    tets.insert(tets.end(), g.mesh.tets.begin() + 4 * t, g.mesh.tets.begin() + 4 * t + 4);
    ids.push_back(static_cast<std::uint32_t>(t));
  }
  const Vec3d origin{0, 0, 0};
  TetVolume volume;
  Bvh bvh;
  const PointSource points{g.mesh.points.data(), ScalarKind::f64, nullptr, ScalarKind::f64,
                           g.mesh.point_count()};
  const FieldSource field{g.field.data(), ScalarKind::f64, g.field.size()};
  load_volume(volume, bvh, tets, {}, ids, points, field, {}, &origin);
  const WalkStructure walk = build_walk_structure(volume);
  return render_volume(volume, walk, test::benchmark_camera(test::scaled_side(96)),
                       options(termination, unit_distance), stats);
}

void check_partition(const std::function<int(std::size_t)>& owner, const char* what) {
  const auto w = world();
  const VolumeFragmentImage mine = render_piece(owner, w.rank);
  Framebuffer image;
  FragmentCompositeStats stats;
  ASSERT_EQ(composite_fragments(mine, MPI_COMM_WORLD, 0, image, {}, &stats), MPI_SUCCESS) << what;
  // Every rank merges its stripe's fragments of all ranks: together, every fragment once.
  std::uint64_t merged = stats.fragments;
  MPI_Allreduce(MPI_IN_PLACE, &merged, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  std::uint64_t sent = mine.fragments.size();
  MPI_Allreduce(MPI_IN_PLACE, &sent, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(merged, sent) << what;
  if (w.rank != 0) return;
  VolumeFragmentImage whole = render_piece([](std::size_t) { return 0; }, 0);
  const Framebuffer expected = resolve(whole);
  ASSERT_EQ(image.pixel_count(), expected.pixel_count());
  std::size_t covered = 0;
  for (std::size_t p = 0; p < expected.pixel_count(); ++p) {
    covered += expected.rgba[4 * p + 3] > 0.05f;
    for (int c = 0; c < 4; ++c) {
      ASSERT_EQ(image.rgba[4 * p + c], expected.rgba[4 * p + c]) << what << " pixel " << p;
    }
    ASSERT_EQ(image.depth[p], expected.depth[p]) << what << " pixel " << p;
    ASSERT_EQ(image.hit[p], expected.hit[p]) << what << " pixel " << p;
  }
  EXPECT_GT(covered, expected.pixel_count() / 10) << what;
  EXPECT_GE(merged, whole.fragments.size()) << what;
}

double centroid_x(std::size_t t) {
  double x = 0;
  for (int k = 0; k < 4; ++k) x += scene().mesh.points[3 * scene().mesh.tets[4 * t + k]];
  return x / 4;
}

TEST(FragmentComposite, SlabsGiveTheOneRankImage) {
  const int ranks = world().size;
  check_partition(
      [ranks](std::size_t t) {
        return std::clamp(static_cast<int>((centroid_x(t) + 1) / 2 * ranks), 0, ranks - 1);
      },
      "slabs");
}

TEST(FragmentComposite, RandomPartitionGivesTheOneRankImage) {
  const int ranks = world().size;
  auto owners = std::make_shared<std::vector<int>>(scene().mesh.tet_count());
  std::mt19937 rng(11);
  for (int& o : *owners) o = std::uniform_int_distribution<int>(0, ranks - 1)(rng);
  check_partition([owners](std::size_t t) { return (*owners)[t]; }, "random");
}

// Early termination on several ranks: each rank stops its own stretch of a ray once that
// stretch is `termination` opaque, not knowing what lies in front. What it leaves out lies behind
// at least that opacity, so each channel of the composited pixel is within 1 - termination of
// the exact image (docs/volume.md), however the tets are split. Checked against the exact
// one-rank image at 0.9 and 0.99, with opacities ten times the other tests' so that rays do
// become that opaque within one slab.
TEST(FragmentComposite, EarlyTerminationOnSplitRaysStaysWithinItsTolerance) {
  const auto w = world();
  const int ranks = w.size;
  const auto slabs = [ranks](std::size_t t) {
    return std::clamp(static_cast<int>((centroid_x(t) + 1) / 2 * ranks), 0, ranks - 1);
  };
  constexpr double kUnitDistance = 0.05;
  VolumeFragmentImage whole = render_piece([](std::size_t) { return 0; }, 0, 1, kUnitDistance);
  const Framebuffer exact = resolve(whole);
  for (const double termination : {0.9, 0.99}) {
    VolumeRenderStats stats;
    const VolumeFragmentImage mine =
        render_piece(slabs, w.rank, termination, kUnitDistance, &stats);
    Framebuffer image;
    ASSERT_EQ(composite_fragments(mine, MPI_COMM_WORLD, 0, image), MPI_SUCCESS);
    std::uint64_t terminated = stats.terminated_runs;
    MPI_Allreduce(MPI_IN_PLACE, &terminated, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    if (w.rank != 0) continue;
    EXPECT_GT(terminated, exact.pixel_count() / 100) << termination;
    ASSERT_EQ(image.pixel_count(), exact.pixel_count());
    const float tolerance = static_cast<float>(1 - termination) + 1e-6f;
    double largest = 0;
    for (std::size_t p = 0; p < exact.pixel_count(); ++p) {
      for (int c = 0; c < 4; ++c) {
        const float difference = std::abs(image.rgba[4 * p + c] - exact.rgba[4 * p + c]);
        ASSERT_LE(difference, tolerance) << termination << " pixel " << p << " channel " << c;
        largest = std::max(largest, double{difference});
      }
    }
    // The bound is not idle: some pixels do lose what lay behind the cut.
    EXPECT_GT(largest, 0.05 * (1 - termination)) << termination;
  }
}

// Rank r's surface layers of pixel p (transparent isosurfaces, zero length): depths from a few
// values so that ties across ranks occur, keys unique over the ranks, some layers opaque.
std::vector<Fragment> rank_layers(std::size_t p, int rank) {
  std::mt19937 rng(static_cast<unsigned>(p * 131 + static_cast<std::size_t>(rank) * 7 + 1));
  std::vector<Fragment> layers(std::uniform_int_distribution<std::size_t>(0, 6)(rng));
  for (std::size_t k = 0; k < layers.size(); ++k) {
    Fragment& f = layers[k];
    f.depth_in = f.depth_out = static_cast<float>(std::uniform_int_distribution<int>(1, 8)(rng));
    f.key = static_cast<std::uint32_t>(100 * rank + k);
    const float alpha = std::uniform_int_distribution<int>(0, 9)(rng) == 0 ? 1.0f : 0.4f;
    for (int c = 0; c < 3; ++c) f.rgba[c] = alpha * 0.1f * static_cast<float>(c + k);
    f.rgba[3] = alpha;
  }
  return layers;
}

// How a rank hands its layers of a pixel to the compositor: its own nearest ones (as
// trace_layers peels), all of them in order (lists of up to six: the merge's general case, and
// the sort where they are too many), or all of them in reverse (which the merge must sort).
enum class Handed { kept, all_in_order, reversed };

FragmentImage rank_image(int rank, int width, int height, std::size_t max_layers,
                         Handed handed = Handed::kept) {
  FragmentImage image;
  image.width = width;
  image.height = height;
  image.begin.push_back(0);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    std::vector<Fragment> layers = rank_layers(p, rank);
    const std::size_t kept = kept_layers(layers, max_layers);  // sorts them
    if (handed == Handed::kept) layers.resize(kept);
    if (handed == Handed::reversed) std::reverse(layers.begin(), layers.end());
    image.fragments.insert(image.fragments.end(), layers.begin(), layers.end());
    image.begin.push_back(static_cast<std::uint32_t>(image.fragments.size()));
  }
  return image;
}

FragmentImage rank_image(int rank, std::size_t pixels, std::size_t max_layers) {
  return rank_image(rank, static_cast<int>(pixels), 1, max_layers);
}

// The layers a pixel keeps, worked out here rather than by kept_layers: `all` sorted by the tie
// rule of docs/architecture.md §3 (depth, then the smaller key) and cut after the first opaque one
// or max_layers; returns how many.
std::size_t nearest_layers(std::vector<Fragment>& all, std::size_t max_layers) {
  std::sort(all.begin(), all.end(), [](const Fragment& a, const Fragment& b) {
    return std::tie(a.depth_in, a.key) < std::tie(b.depth_in, b.key);
  });
  const std::size_t limit = std::min(all.size(), max_layers);
  for (std::size_t k = 0; k < limit; ++k) {
    if (all[k].rgba[3] >= 1) return k + 1;
  }
  return limit;
}

// The merge keeps, of all ranks' layers of a pixel, the nearest max_layers in the tie order up
// to the first opaque one: exactly the layers of one rank holding every surface.
TEST(FragmentComposite, KeepsTheNearestLayersOfAllRanks) {
  constexpr std::size_t kPixels = 500, kMaxLayers = 3;
  const auto w = world();
  FragmentImage merged;
  ASSERT_EQ(gather_fragments(rank_image(w.rank, kPixels, kMaxLayers), MPI_COMM_WORLD, 0, kMaxLayers,
                             merged),
            MPI_SUCCESS);
  if (w.rank != 0) return;
  ASSERT_EQ(merged.pixel_count(), kPixels);
  std::size_t capped = 0;
  for (std::size_t p = 0; p < kPixels; ++p) {
    std::vector<Fragment> all;
    for (int r = 0; r < w.size; ++r) {
      const std::vector<Fragment> layers = rank_layers(p, r);
      all.insert(all.end(), layers.begin(), layers.end());
    }
    const std::size_t kept = nearest_layers(all, kMaxLayers);
    capped += kept < all.size();
    const auto got = merged.pixel(p);
    ASSERT_EQ(got.size(), kept) << "pixel " << p;
    for (std::size_t k = 0; k < kept; ++k) {
      EXPECT_EQ(got[k].depth_in, all[k].depth_in) << "pixel " << p << " layer " << k;
      EXPECT_EQ(got[k].key, all[k].key) << "pixel " << p << " layer " << k;
    }
  }
  EXPECT_GT(capped, kPixels / 4) << "the cap and the opaque cut must matter";
}

// Pixel p's kept layers of all ranks, nearest first, worked out here (nearest_layers).
std::vector<Fragment> all_ranks_kept(std::size_t p, int ranks, std::size_t max_layers) {
  std::vector<Fragment> all;
  for (int r = 0; r < ranks; ++r) {
    const std::vector<Fragment> layers = rank_layers(p, r);
    all.insert(all.end(), layers.begin(), layers.end());
  }
  all.resize(nearest_layers(all, max_layers));
  return all;
}

// The stripes' compositor (each rank merges and blends a stripe, the root gathers them) gives
// each pixel the over of the nearest max_layers of all ranks, front to back in double, with the
// nearest one's key and its depth as the stripe hook makes it, however the ranks hand in their
// layers (Handed). The image is 41 x 13, so that stripes end inside rows.
void expect_stripes_blend_the_nearest_layers(Handed handed) {
  constexpr int kWidth = 41, kHeight = 13;
  constexpr std::size_t kMaxLayers = 3;
  const auto w = world();
  FragmentCompositeOptions options;
  options.max_layers = kMaxLayers;
  // This rank's first pixel and pixel count as the hook saw them (-1: never called).
  std::vector<long long> stripe = {-1, -1};
  options.stripe_depths = [&](std::size_t first, std::span<float> depth) {
    stripe = {static_cast<long long>(first), static_cast<long long>(depth.size())};
    for (float& d : depth) d = 2 * d + 1;
  };
  Framebuffer image;
  FragmentWorkspace<Fragment> workspace;
  for (int frame = 0; frame < 2; ++frame) {  // the second reuses the workspace and the image
    ASSERT_EQ(composite_fragments(rank_image(w.rank, kWidth, kHeight, kMaxLayers, handed),
                                  MPI_COMM_WORLD, 0, image, options, nullptr, &workspace),
              MPI_SUCCESS);
  }
  // The stripes cover the image once, in rank order.
  std::vector<long long> stripes(2 * static_cast<std::size_t>(w.size));
  MPI_Gather(stripe.data(), 2, MPI_LONG_LONG, stripes.data(), 2, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  if (w.rank != 0) return;
  long long next = 0;
  for (int r = 0; r < w.size; ++r) {
    EXPECT_EQ(stripes[2 * static_cast<std::size_t>(r)], next) << "rank " << r;
    next += stripes[2 * static_cast<std::size_t>(r) + 1];
  }
  EXPECT_EQ(next, kWidth * kHeight);
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    const std::vector<Fragment> kept = all_ranks_kept(p, w.size, kMaxLayers);
    double out[4] = {0, 0, 0, 0};
    for (const Fragment& f : kept) {
      const double through = 1.0 - out[3];
      for (int c = 0; c < 4; ++c) out[c] += through * f.rgba[c];
    }
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(image.rgba[4 * p + c], static_cast<float>(out[c])) << "pixel " << p;
    const float depth = kept.empty() ? std::numeric_limits<float>::infinity() : kept[0].depth_in;
    EXPECT_EQ(image.depth[p], 2 * depth + 1) << "pixel " << p;
    EXPECT_EQ(image.hit[p], kept.empty() ? kNoHit : kept[0].key) << "pixel " << p;
  }
}

TEST(FragmentStripes, BlendTheNearestLayersOfAllRanksFromTheirKeptOnes) {
  expect_stripes_blend_the_nearest_layers(Handed::kept);
}

TEST(FragmentStripes, BlendTheNearestLayersOfAllRanksFromAllOfThemInOrder) {
  expect_stripes_blend_the_nearest_layers(Handed::all_in_order);
}

TEST(FragmentStripes, SortLayersARankHandsInOutOfOrder) {
  expect_stripes_blend_the_nearest_layers(Handed::reversed);
}

// Images of different sizes on different ranks, or a malformed one, are refused on every rank
// alike, before any fragment moves.
TEST(FragmentStripes, RefuseImagesOfDifferentSizesOnEveryRank) {
  const auto w = world();
  FragmentImage image = rank_image(w.rank, 20, 3, 2);
  if (w.size > 1 && w.rank == w.size - 1) {
    image = rank_image(w.rank, 21, 3, 2);
  } else if (w.size == 1) {
    image.begin.pop_back();  // one offset short
  }
  Framebuffer out;
  EXPECT_EQ(composite_fragments(image, MPI_COMM_WORLD, 0, out), MPI_ERR_SIZE);
  EXPECT_EQ(out.pixel_count(), 0u);
}

// A root out of range, or one rank naming another root than the others, is refused on every
// rank before any fragment moves.
TEST(FragmentStripes, RefuseARootOutOfRangeOrNotTheSameOnEveryRank) {
  const auto w = world();
  const FragmentImage image = rank_image(w.rank, 20, 3, 2);
  Framebuffer out;
  EXPECT_EQ(composite_fragments(image, MPI_COMM_WORLD, w.size, out), MPI_ERR_ROOT);
  EXPECT_EQ(composite_fragments(image, MPI_COMM_WORLD, -1, out), MPI_ERR_ROOT);
  if (w.size > 1) {
    const int root = w.rank == w.size - 1 ? 1 : 0;
    EXPECT_EQ(composite_fragments(image, MPI_COMM_WORLD, root, out), MPI_ERR_ROOT);
  }
  EXPECT_EQ(out.pixel_count(), 0u);
}

// A rank whose stripe fails after the exchange (the depth hook throws; memory runs out) does not
// leave the others waiting in the gather: every rank returns the failure, and the next
// composite on the same ranks works.
TEST(FragmentStripes, AFailedStripeOnOneRankIsAnErrorOnEveryRank) {
  const auto w = world();
  const FragmentImage image = rank_image(w.rank, 41, 13, 3);
  const int failing = w.size - 1;
  Framebuffer out;
  for (const bool out_of_memory : {false, true}) {
    FragmentCompositeOptions options;
    options.stripe_depths = [&](std::size_t, std::span<float>) {
      if (w.rank != failing) return;
      if (out_of_memory) throw std::bad_alloc();
      throw std::runtime_error("the hook failed");
    };
    EXPECT_EQ(composite_fragments(image, MPI_COMM_WORLD, 0, out, options),
              out_of_memory ? MPI_ERR_NO_MEM : MPI_ERR_OTHER);
  }
  ASSERT_EQ(composite_fragments(image, MPI_COMM_WORLD, 0, out), MPI_SUCCESS);
  if (w.rank == 0) {
    EXPECT_EQ(out.pixel_count(), std::size_t{41 * 13});
  }
}

}  // namespace
}  // namespace tetray::render
