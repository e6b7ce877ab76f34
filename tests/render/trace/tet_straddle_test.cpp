// The leaf's batched straddle test (render/tet_straddle.hpp) against the one-tet test of the
// same rule: random tets over a small vertex store, every batch size from 1 to the SIMD width,
// batches ending at the last tet of the volume, isovalues on vertex values, between them and
// outside their range. And the corner columns it is built on (simd::quad_columns), on groups
// that end at an inaccessible page: nothing past the last group may be read. Every copy of the
// straddle code is checked: the baseline's and each instruction-set variant's, whose SIMD width
// and corner loads differ (culling_copies.hpp).
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <string>

#include "culling_copies.hpp"

namespace tetray::test {
namespace {

using render::IsoSet;
using render::TetVolume;

TetVolume random_volume(std::mt19937& rng, int vertices, int tets) {
  TetVolume volume;
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int v = 0; v < vertices; ++v) volume.vertices.push_back({0, 0, 0, value(rng)});
  std::uniform_int_distribution<std::int32_t> corner(0, vertices - 1);
  for (int t = 0; t < tets; ++t)
    volume.tets.push_back({{corner(rng), corner(rng), corner(rng), corner(rng)}});
  return volume;
}

bool tet_straddles(const TetVolume& volume, std::uint32_t t, const IsoSet& isos) {
  float lo = volume.vertices[volume.tets[t].v[0]].f, hi = lo;
  for (std::int32_t v : volume.tets[t].v) {
    lo = std::min(lo, volume.vertices[v].f);
    hi = std::max(hi, volume.vertices[v].f);
  }
  return isos.straddled_by(lo, hi);
}

IsoSet isovalues(std::initializer_list<float> values) {
  IsoSet isos;
  for (float v : values) isos.values[isos.count++] = v;
  return isos;
}

class TetStraddle : public CullingCopies {};
TETRAY_FOR_EACH_CULLING_COPY(TetStraddle);

TEST_P(TetStraddle, EveryBatchMatchesTheOneTetTest) {
  std::mt19937 rng(7);
  const TetVolume volume = random_volume(rng, 40, 200);
  const float on_vertex = volume.vertices[3].f;
  const IsoSet sets[] = {isovalues({0.0f}), isovalues({-0.5f, 0.25f, 0.8f}), isovalues({on_vertex}),
                         isovalues({2.0f}), isovalues({-2.0f})};
  const auto tets = static_cast<std::uint32_t>(volume.tets.size());
  int straddling = 0;
  for (const IsoSet& isos : sets) {
    for (int count = 1; count <= kernels().simd_width; ++count) {
      // Every start, the last batches ending exactly at the volume's last tet.
      for (std::uint32_t first = 0; first + count <= tets; ++first) {
        const std::uint64_t bits = kernels().straddling_in_batch(volume, first, count, isos);
        for (int k = 0; k < count; ++k) {
          const bool expected = tet_straddles(volume, first + k, isos);
          straddling += expected;
          ASSERT_EQ((bits >> k) & 1, expected ? 1u : 0u)
              << "tet " << first + k << " in a batch of " << count << " from " << first;
        }
        ASSERT_EQ(bits >> count, 0u) << "bits past the batch, count " << count;
      }
    }
  }
  EXPECT_GT(straddling, 0);  // the sets above do cut tets
}

// A leaf's tets in lane batches (leaf_straddling_tets): every leaf size up to 64 tets, at every
// start of the volume, bit for bit the one-tet test, nothing past the leaf.
TEST_P(TetStraddle, EveryLeafMatchesTheOneTetTest) {
  std::mt19937 rng(11);
  const TetVolume volume = random_volume(rng, 40, 120);
  const IsoSet isos = isovalues({-0.3f, 0.4f});
  const auto tets = static_cast<std::uint32_t>(volume.tets.size());
  int straddling = 0;
  for (std::uint32_t count = 1; count <= 64; ++count)
    for (std::uint32_t first = 0; first + count <= tets; first += 7) {
      const std::uint64_t bits = kernels().straddling_in_leaf(volume, first, count, isos);
      for (std::uint32_t k = 0; k < count; ++k) {
        const bool expected = tet_straddles(volume, first + k, isos);
        straddling += expected;
        ASSERT_EQ((bits >> k) & 1, expected ? 1u : 0u)
            << "tet " << first + k << " in a leaf of " << count << " from " << first;
      }
      if (count < 64) {
        ASSERT_EQ(bits >> count, 0u) << "bits past the leaf, count " << count;
      }
    }
  EXPECT_GT(straddling, 0);
}

// Two pages, the second inaccessible: groups placed to end at the boundary fault if read past.
class GuardedPage {
 public:
  GuardedPage() : page_(static_cast<std::size_t>(sysconf(_SC_PAGESIZE))) {
    void* memory =
        mmap(nullptr, 2 * page_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (memory != MAP_FAILED) base_ = static_cast<std::byte*>(memory);
    if (base_ && mprotect(base_ + page_, page_, PROT_NONE) != 0) base_ = nullptr;
  }
  ~GuardedPage() {
    if (base_) munmap(base_, 2 * page_);
  }
  GuardedPage(const GuardedPage&) = delete;
  GuardedPage& operator=(const GuardedPage&) = delete;

  bool ok() const { return base_ != nullptr; }
  // `count` int32 values ending where the inaccessible page begins.
  std::int32_t* ints_before_guard(int count) const {
    return reinterpret_cast<std::int32_t*>(base_ + page_) - count;
  }

 private:
  std::size_t page_;
  std::byte* base_ = nullptr;
};

TEST_P(TetStraddle, CornerColumnsReadNothingPastTheGroups) {
  const GuardedPage guarded;
  ASSERT_TRUE(guarded.ok());
  const int width = kernels().simd_width;
  for (int count = 1; count <= width; ++count) {
    std::int32_t* groups = guarded.ints_before_guard(4 * count);
    for (int i = 0; i < 4 * count; ++i) groups[i] = 1000 + i;
    std::int32_t column[4][16];
    kernels().quad_columns(groups, count, column);
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < width; ++k)
        EXPECT_EQ(column[c][k], k < count ? 1000 + 4 * k + c : 0)
            << "element " << c << ", lane " << k << ", " << count << " groups";
  }
}

// The copies' widths: the variants' registers hold 4, 8 and 16 floats (a copy compiled for the
// wrong target would be checked at the wrong width).
TEST_P(TetStraddle, TheCopysWidthIsItsTargets) {
  const std::string& name = GetParam().name;
  const int expected = name == "avx512" ? 16 : name == "avx2" ? 8 : name == "sse4_2" ? 4 : 0;
  if (expected != 0) {
    EXPECT_EQ(kernels().simd_width, expected) << name;
  } else {
    EXPECT_EQ(kernels().simd_width, render::simd::kWidth) << "the baseline's, as compiled here";
  }
}

}  // namespace
}  // namespace tetray::test
