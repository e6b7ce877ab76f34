// One SIMD vocabulary for the kernels (docs/architecture.md §7): the few operations they need, over
// xsimd's widest float batch for the build target (AVX-512 where the CPU has it) and over plain
// float for the single-ray path. Both spellings do the same IEEE operations (no fused
// multiply-add), so a pixel gets bitwise the same result whatever the packet size.
#pragma once

#include <xsimd/xsimd.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace tetray::render::simd {

using Floats = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;
using Ints = xsimd::batch<std::int32_t>;
inline constexpr int kWidth = static_cast<int>(Floats::size);

// Four floats in one register: a Vertex (x, y, z, f) or one side of a 4D bound, so a bound
// grows by one min and one max per vertex (Wald et al. 2007, §6.2).
using Float4 = xsimd::make_sized_batch_t<float, 4>;

using Mask4 = Float4::batch_bool_type;

// The four floats of a 16-byte aligned struct (a Vertex) as one aligned load.
template <typename T>
inline Float4 load_float4(const T& v) {
  static_assert(sizeof(T) == 4 * sizeof(float) && alignof(T) >= 16);
  alignas(16) float xyzw[4];
  std::memcpy(xyzw, &v, sizeof xyzw);  // one aligned load once optimized
  return Float4::load_aligned(xyzw);
}

// Four 16-byte structs (rows) turned into their four components (columns): lane k of column c
// is component c of row k.
inline void transpose4(const Float4 (&rows)[4], Float4 (&columns)[4]) {
  using Pairs = xsimd::make_sized_batch_t<double, 2>;  // two floats moved as one double
  const Pairs xy01 = xsimd::bitwise_cast<Pairs>(xsimd::zip_lo(rows[0], rows[1]));
  const Pairs xy23 = xsimd::bitwise_cast<Pairs>(xsimd::zip_lo(rows[2], rows[3]));
  const Pairs zw01 = xsimd::bitwise_cast<Pairs>(xsimd::zip_hi(rows[0], rows[1]));
  const Pairs zw23 = xsimd::bitwise_cast<Pairs>(xsimd::zip_hi(rows[2], rows[3]));
  columns[0] = xsimd::bitwise_cast<Float4>(xsimd::zip_lo(xy01, xy23));
  columns[1] = xsimd::bitwise_cast<Float4>(xsimd::zip_hi(xy01, xy23));
  columns[2] = xsimd::bitwise_cast<Float4>(xsimd::zip_lo(zw01, zw23));
  columns[3] = xsimd::bitwise_cast<Float4>(xsimd::zip_hi(zw01, zw23));
}

// Lanes (1, 2, 3, 0) of v: lane k gets lane k + 1, cyclically.
inline Float4 next_lane(Float4 v) {
  return xsimd::swizzle(
      v, xsimd::batch_constant<xsimd::batch<std::uint32_t, Float4::arch_type>, 1, 2, 3, 0>());
}

// Lane k of the result is lane lanes[k] of v (lanes aligned to 16 bytes): one shuffle where the
// CPU has a variable one (AVX's vpermilps).
inline Float4 permute(Float4 v, const std::int32_t* lanes) {
#if XSIMD_WITH_AVX
  return _mm_permutevar_ps(v, _mm_load_si128(reinterpret_cast<const __m128i*>(lanes)));
#else
  alignas(16) float in[4], out[4];
  v.store_aligned(in);
  for (int k = 0; k < 4; ++k) out[k] = in[lanes[k]];
  return Float4::load_aligned(out);
#endif
}

// Lanes 0 + 1 + 2 of v, in that order.
inline float sum3(Float4 v) {
  alignas(16) float lanes[4];
  v.store_aligned(lanes);
  return lanes[0] + lanes[1] + lanes[2];
}

// Bit k set when lane k of `m` is set.
inline int bits4(Mask4 m) {
#if XSIMD_WITH_SSE2
  return _mm_movemask_ps(m);
#else
  alignas(16) bool lanes[4];
  m.store_aligned(lanes);
  return int{lanes[0]} | int{lanes[1]} << 1 | int{lanes[2]} << 2 | int{lanes[3]} << 3;
#endif
}

// Lanewise lexicographic a < b over N components: the first component that differs decides.
// Compares only, so the result is exact and needs no branch.
template <int N, typename Batch>
inline auto lexicographic_less(const Batch* a, const Batch* b) {
  auto less = a[N - 1] < b[N - 1];
  for (int c = N - 2; c >= 0; --c) less = (a[c] < b[c]) | ((a[c] == b[c]) & less);
  return less;
}

// Lane type for a packet of `rays` rays: a full batch when it fills one, else plain float.
template <int rays>
struct LaneTypes {
  using F = Floats;
  using M = Mask;
  static constexpr int width = kWidth;
};
template <>
struct LaneTypes<1> {
  using F = float;
  using M = bool;
  static constexpr int width = 1;
};

inline Floats load(const float* p, Floats) { return Floats::load_aligned(p); }
inline float load(const float* p, float) { return *p; }
inline void store(float* p, Floats v) { v.store_aligned(p); }
inline void store(float* p, float v) { *p = v; }

// Compare and select, as the min and max instructions define them (the second operand where the
// two are equal or either is NaN): GCC 12 reports its own AVX-512 min and max as reading an
// uninitialized value.
inline Floats vmin(Floats a, Floats b) { return xsimd::select(a < b, a, b); }
inline float vmin(float a, float b) { return a < b ? a : b; }
inline Floats vmax(Floats a, Floats b) { return xsimd::select(a > b, a, b); }
inline float vmax(float a, float b) { return a > b ? a : b; }
inline Floats select(Mask m, Floats a, Floats b) { return xsimd::select(m, a, b); }
inline float select(bool m, float a, float b) { return m ? a : b; }
inline bool any(Mask m) { return xsimd::any(m); }
inline bool any(bool m) { return m; }

// The lanes of p[0, width) where `m` is set become `value`: a read, blend and write, which the
// per-thread packet arrays allow (no masked store needed). Integers go through the float mask.
inline void store_where(Mask m, Floats value, float* p) {
  xsimd::select(m, value, Floats::load_aligned(p)).store_aligned(p);
}
template <typename T>
inline void store_where(Mask m, T value, T* p) {
  static_assert(sizeof(T) == sizeof(float) && std::is_integral_v<T>);
  using Lanes = xsimd::batch<T>;
  const Floats old = xsimd::bitwise_cast<Floats>(Lanes::load_aligned(p));
  const Floats fresh = xsimd::bitwise_cast<Floats>(Lanes(value));
  xsimd::bitwise_cast<Lanes>(xsimd::select(m, fresh, old)).store_aligned(p);
}
template <typename T>
inline void store_where(bool m, T value, T* p) {
  if (m) *p = value;
}

// 0, 1, 2, ... in the lanes of an integer batch.
inline Ints lane_indices() {
  static_assert(kWidth <= 16);
  alignas(64) static constexpr std::int32_t kLanes[16] = {0, 1, 2,  3,  4,  5,  6,  7,
                                                          8, 9, 10, 11, 12, 13, 14, 15};
  return Ints::load_aligned(kLanes);
}

// A load per lane: the gathers below where the CPU has no gather instruction.
template <typename Batch, typename T>
inline Batch gather_each_lane(const T* base, Ints index) {
  alignas(64) std::int32_t lanes[kWidth];
  alignas(64) T out[kWidth];
  index.store_aligned(lanes);
  for (int k = 0; k < kWidth; ++k) out[k] = base[lanes[k]];
  return Batch::load_aligned(out);
}

// Lane k of the result is base[index[k]]: one gather instruction where the CPU has one (xsimd 8
// falls back to a load per lane). The AVX-512 forms take an explicit start value: GCC 12 reports
// the undefined one of the plain forms as uninitialized.
inline Floats gather(const float* base, Ints index) {
#if XSIMD_WITH_AVX512F
  return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), 0xffff, index, base, sizeof(float));
#elif XSIMD_WITH_AVX2
  return _mm256_i32gather_ps(base, index, sizeof(float));
#else
  return gather_each_lane<Floats>(base, index);
#endif
}
inline Ints gather(const std::int32_t* base, Ints index) {
#if XSIMD_WITH_AVX512F
  return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xffff, index, base,
                                     sizeof(std::int32_t));
#elif XSIMD_WITH_AVX2
  return _mm256_i32gather_epi32(base, index, sizeof(std::int32_t));
#else
  return gather_each_lane<Ints>(base, index);
#endif
}

// Lane k of column c is component c of the row rows + 4 row[k] (rows of four floats, 16-byte
// aligned: Vertex), k < kWidth. AVX-512 and AVX load the rows whole, four to a register (row
// 4 l + p in 128-bit lane l of register p), and move them into columns by in-lane unpacks: a
// quarter of the loads of one gather per component, which a tile's set-up of a lane batch of
// tets had waited on (gather_tets). (The masked AVX-512 forms: see gather.)
inline void gather_rows(const float* rows, const std::int32_t* row, Floats (&column)[4]) {
  auto at = [&](int k) { return _mm_load_ps(rows + 4 * static_cast<std::ptrdiff_t>(row[k])); };
#if XSIMD_WITH_AVX512F
  auto rows_of = [&](int p) {
    const __m512 v = _mm512_insertf32x4(_mm512_maskz_broadcast_f32x4(0xf, at(p)), at(4 + p), 1);
    return _mm512_insertf32x4(_mm512_insertf32x4(v, at(8 + p), 2), at(12 + p), 3);
  };
  const __m512 r0 = rows_of(0), r1 = rows_of(1), r2 = rows_of(2), r3 = rows_of(3);
  // Per 128-bit lane: (x, x, y, y) and (z, z, f, f) of rows p = 0, 1 and of rows p = 2, 3.
  const __m512d xy01 = _mm512_castps_pd(_mm512_mask_unpacklo_ps(r0, 0xffff, r0, r1));
  const __m512d zf01 = _mm512_castps_pd(_mm512_mask_unpackhi_ps(r0, 0xffff, r0, r1));
  const __m512d xy23 = _mm512_castps_pd(_mm512_mask_unpacklo_ps(r2, 0xffff, r2, r3));
  const __m512d zf23 = _mm512_castps_pd(_mm512_mask_unpackhi_ps(r2, 0xffff, r2, r3));
  column[0] = _mm512_castpd_ps(_mm512_mask_unpacklo_pd(xy01, 0xff, xy01, xy23));
  column[1] = _mm512_castpd_ps(_mm512_mask_unpackhi_pd(xy01, 0xff, xy01, xy23));
  column[2] = _mm512_castpd_ps(_mm512_mask_unpacklo_pd(zf01, 0xff, zf01, zf23));
  column[3] = _mm512_castpd_ps(_mm512_mask_unpackhi_pd(zf01, 0xff, zf01, zf23));
#elif XSIMD_WITH_AVX
  auto rows_of = [&](int p) { return _mm256_set_m128(at(4 + p), at(p)); };
  const __m256 r0 = rows_of(0), r1 = rows_of(1), r2 = rows_of(2), r3 = rows_of(3);
  const __m256d xy01 = _mm256_castps_pd(_mm256_unpacklo_ps(r0, r1));
  const __m256d zf01 = _mm256_castps_pd(_mm256_unpackhi_ps(r0, r1));
  const __m256d xy23 = _mm256_castps_pd(_mm256_unpacklo_ps(r2, r3));
  const __m256d zf23 = _mm256_castps_pd(_mm256_unpackhi_ps(r2, r3));
  column[0] = _mm256_castpd_ps(_mm256_unpacklo_pd(xy01, xy23));
  column[1] = _mm256_castpd_ps(_mm256_unpackhi_pd(xy01, xy23));
  column[2] = _mm256_castpd_ps(_mm256_unpacklo_pd(zf01, zf23));
  column[3] = _mm256_castpd_ps(_mm256_unpackhi_pd(zf01, zf23));
#else
  static_assert(kWidth == 4);
  const Float4 r[4] = {at(0), at(1), at(2), at(3)};
  transpose4(r, column);
#endif
}

// Rounding up and down, and truncation to integers, lanewise or of one float. The AVX-512 forms
// take an explicit start value: GCC 12 reports the undefined one of xsimd's as uninitialized.
inline Floats ceil(Floats v) {
#if XSIMD_WITH_AVX512F
  return _mm512_mask_roundscale_ps(v, 0xffff, v, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
#else
  return xsimd::ceil(v);
#endif
}
inline Floats floor(Floats v) {
#if XSIMD_WITH_AVX512F
  return _mm512_mask_roundscale_ps(v, 0xffff, v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
#else
  return xsimd::floor(v);
#endif
}
inline float ceil(float v) { return std::ceil(v); }
inline float floor(float v) { return std::floor(v); }
// Square roots, correctly rounded in every form (IEEE), so each gives the same bits.
inline Floats sqrt(Floats v) { return xsimd::sqrt(v); }
inline float sqrt(float v) { return std::sqrt(v); }
inline Ints to_int(Floats v) {
#if XSIMD_WITH_AVX512F
  return _mm512_mask_cvttps_epi32(_mm512_setzero_si512(), 0xffff, v);
#else
  return xsimd::to_int(v);
#endif
}

// Lane k of the result is table[index[k]], from a table of 16 int32 (64-byte aligned) and
// indices in [0, 16): one permute where the registers hold 16 lanes.
inline Ints lookup16(const std::int32_t* table, Ints index) {
#if XSIMD_WITH_AVX512F
  return _mm512_permutexvar_epi32(index, _mm512_load_si512(table));
#else
  return gather(table, index);
#endif
}

// Column c of the result holds element c of each of `count` consecutive groups of four int32
// (1 <= count <= kWidth; a tet's corner indices), group k in lane k; lanes past `count` hold 0.
// AVX-512 loads the groups as they lie and moves them into columns with eight two-register
// permutes, a fraction of the cost of the four gathers the other targets use.
inline void quad_columns(const std::int32_t* groups, int count, Ints (&column)[4]) {
#if XSIMD_WITH_AVX512F
  static_assert(kWidth == 16);
  auto load = [&](int q) {  // groups 4q .. 4q + 3, the lanes past the last group zero
    const int valid = std::clamp(4 * (count - 4 * q), 0, 16);
    const auto lanes = static_cast<__mmask16>((1u << valid) - 1);
    // A register wholly past the groups loads nothing, from an address within them.
    return _mm512_maskz_loadu_epi32(lanes, groups + 16 * std::min(q, (count - 1) / 4));
  };
  // From two registers of four groups each: element e of the eight groups in lanes 0-7, element
  // e + 1 in lanes 8-15 (kPairs[0]: e = 0, kPairs[1]: e = 2); then from two such registers, the
  // lower or upper halves of each (kHalves).
  alignas(64) static constexpr std::int32_t kPairs[2][16] = {
      {0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29},
      {2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27, 31}};
  alignas(64) static constexpr std::int32_t kHalves[2][16] = {
      {0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23},
      {8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31}};
  const __m512i q[4] = {load(0), load(1), load(2), load(3)};
  for (int p = 0; p < 2; ++p) {
    const __m512i pair = _mm512_load_si512(kPairs[p]);
    const __m512i first = _mm512_permutex2var_epi32(q[0], pair, q[1]);
    const __m512i second = _mm512_permutex2var_epi32(q[2], pair, q[3]);
    for (int h = 0; h < 2; ++h)
      column[2 * p + h] = _mm512_permutex2var_epi32(first, _mm512_load_si512(kHalves[h]), second);
  }
#else
  const Ints lane = lane_indices(), last(count - 1);
  const Ints first_element = xsimd::select(lane < last, lane, last) * 4;  // never past the groups
  for (int c = 0; c < 4; ++c)
    column[c] = xsimd::select(lane <= last, gather(groups, first_element + c), Ints(0));
#endif
}

#if XSIMD_WITH_AVX512F
// The lower (k = 0) or upper (k = 1) eight floats of v. AVX-512F alone has the 64-bit form of the
// extract, here masked: GCC 12 reports the undefined start value of the plain form (and of the
// cast to the lower half) as uninitialized where a caller inlines it twice.
template <int k>
inline __m256 half_of(__m512 v) {
  return _mm256_castpd_ps(
      _mm512_mask_extractf64x4_pd(_mm256_setzero_pd(), 0xf, _mm512_castps_pd(v), k));
}
#endif

// Component-wise minimum and maximum of the rows rows[index[k]], k in [0, count), count >= 1,
// each row four floats (16-byte aligned). AVX-512 holds four rows in a register, so a leaf of a
// dozen vertices takes three steps (a row repeated past the end changes neither bound); the
// other targets grow two bounds in turn (two independent chains).
inline void min_max_rows(const float* rows, const std::uint32_t* index, int count, Float4& lo,
                         Float4& hi) {
#if XSIMD_WITH_AVX512F
  const int last = count - 1;
  // Rows k to k + 3; `clamp`: those past the end repeat the last. Only the final step clamps:
  // clamping every index cost the refit at 14M tets about a tenth (alternating runs).
  auto four_rows = [&](int k, bool clamp) {
    auto row = [&](int j) {
      return _mm_load_ps(rows + 4 * std::size_t{index[clamp ? std::min(k + j, last) : k + j]});
    };
    __m512 v = _mm512_castps128_ps512(row(0));
    v = _mm512_insertf32x4(v, row(1), 1);
    v = _mm512_insertf32x4(v, row(2), 2);
    return _mm512_insertf32x4(v, row(3), 3);
  };
  __m512 low = four_rows(0, count < 4), high = low;
  auto grow = [&](__m512 v) {
    low = _mm512_mask_min_ps(low, 0xffff, low, v);  // masked forms: see gather
    high = _mm512_mask_max_ps(high, 0xffff, high, v);
  };
  int k = 4;
  for (; k + 4 <= count; k += 4) grow(four_rows(k, false));
  if (k < count) grow(four_rows(k, true));
  const __m256 low8 = _mm256_min_ps(half_of<0>(low), half_of<1>(low));
  const __m256 high8 = _mm256_max_ps(half_of<0>(high), half_of<1>(high));
  lo = _mm_min_ps(_mm256_castps256_ps128(low8), _mm256_extractf128_ps(low8, 1));
  hi = _mm_max_ps(_mm256_castps256_ps128(high8), _mm256_extractf128_ps(high8, 1));
#else
  auto row = [&](int k) { return Float4::load_aligned(rows + 4 * std::size_t{index[k]}); };
  Float4 lo_even = row(0), hi_even = lo_even, lo_odd = lo_even, hi_odd = lo_even;
  int k = 1;
  for (; k + 1 < count; k += 2) {
    const Float4 a = row(k), b = row(k + 1);
    lo_even = xsimd::min(lo_even, a);
    hi_even = xsimd::max(hi_even, a);
    lo_odd = xsimd::min(lo_odd, b);
    hi_odd = xsimd::max(hi_odd, b);
  }
  if (k < count) {
    lo_even = xsimd::min(lo_even, row(k));
    hi_even = xsimd::max(hi_even, row(k));
  }
  lo = xsimd::min(lo_even, lo_odd);
  hi = xsimd::max(hi_even, hi_odd);
#endif
}

// Lanes where the unsigned integers at p (aligned for a batch) exceed `value`: compared as
// signed integers with the sign bits flipped, which keeps the unsigned order.
inline Mask greater(const std::uint32_t* p, std::uint32_t value, Floats) {
  using Ints32 = xsimd::batch<std::int32_t>;
  const Ints32 flip(std::numeric_limits<std::int32_t>::min());
  const Ints32 lanes = Ints32::load_aligned(reinterpret_cast<const std::int32_t*>(p)) ^ flip;
  return xsimd::bool_cast(lanes > (Ints32(static_cast<std::int32_t>(value)) ^ flip));
}
inline bool greater(const std::uint32_t* p, std::uint32_t value, float) { return *p > value; }

inline Mask either(Mask a, Mask b) { return a | b; }
inline bool either(bool a, bool b) { return a || b; }
inline Mask both(Mask a, Mask b) { return a & b; }
inline bool both(bool a, bool b) { return a && b; }

// Bit i set when lane i of `m` is set.
// (xsimd 8 has no portable movemask; this header is the one place that knows the registers.)
inline std::uint64_t bits(Mask m) {
#if XSIMD_WITH_AVX512F
  return static_cast<std::uint64_t>(static_cast<__mmask16>(m));
#elif XSIMD_WITH_AVX
  return static_cast<std::uint64_t>(_mm256_movemask_ps(m));
#elif XSIMD_WITH_SSE2
  return static_cast<std::uint64_t>(_mm_movemask_ps(m));
#else
  alignas(64) bool lanes[kWidth];
  m.store_aligned(lanes);
  std::uint64_t b = 0;
  for (int i = 0; i < kWidth; ++i) b |= std::uint64_t{lanes[i]} << i;
  return b;
#endif
}
inline std::uint64_t bits(bool m) { return m ? 1u : 0u; }

// The largest lane (no NaN among them), of a batch or of one float.
inline float max_of(Floats v) {
#if XSIMD_WITH_AVX512F
  // Halves folded with unmasked maxima (GCC 12 reports _mm512_reduce_max_ps's as uninitialized).
  const __m256 upper = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(v), 1));
  const __m256 m8 = _mm256_max_ps(_mm512_castps512_ps256(v), upper);
  __m128 m4 = _mm_max_ps(_mm256_castps256_ps128(m8), _mm256_extractf128_ps(m8, 1));
  m4 = _mm_max_ps(m4, _mm_movehl_ps(m4, m4));
  return _mm_cvtss_f32(_mm_max_ss(m4, _mm_shuffle_ps(m4, m4, 1)));
#else
  alignas(64) float lanes[kWidth];
  v.store_aligned(lanes);
  float m = lanes[0];
  for (int k = 1; k < kWidth; ++k) m = lanes[k] > m ? lanes[k] : m;
  return m;
#endif
}
inline float max_of(float v) { return v; }

// The smallest and the largest of four lanes (no NaN among them); where a batch is four lanes,
// max_of(Floats) serves.
inline float min_of(Float4 v) {
  alignas(16) float lanes[4];
  v.store_aligned(lanes);
  return std::min(std::min(lanes[0], lanes[1]), std::min(lanes[2], lanes[3]));
}
template <typename Four = Float4>
requires(!std::is_same_v<Four, Floats>) inline float max_of(Four v) {
  alignas(16) float lanes[4];
  v.store_aligned(lanes);
  return std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
}

// Bytes one streaming store writes; destinations of stream_copy are aligned to it.
inline constexpr std::size_t kStreamBytes = sizeof(float) * kWidth;

// Copies `bytes` (a multiple of kStreamBytes) from `from` to `to`, both aligned to
// kStreamBytes, with streaming stores: the destination's cache lines are written without being
// read first (a frame is written once and read only after it is done). Call stream_fence()
// before another thread reads them.
inline void stream_copy(void* to, const void* from, std::size_t bytes) {
#if XSIMD_WITH_AVX512F
  for (std::size_t k = 0; k < bytes / kStreamBytes; ++k)
    _mm512_stream_si512(static_cast<__m512i*>(to) + k,
                        _mm512_load_si512(static_cast<const __m512i*>(from) + k));
#elif XSIMD_WITH_AVX
  for (std::size_t k = 0; k < bytes / kStreamBytes; ++k)
    _mm256_stream_si256(static_cast<__m256i*>(to) + k,
                        _mm256_load_si256(static_cast<const __m256i*>(from) + k));
#elif XSIMD_WITH_SSE2
  for (std::size_t k = 0; k < bytes / kStreamBytes; ++k)
    _mm_stream_si128(static_cast<__m128i*>(to) + k,
                     _mm_load_si128(static_cast<const __m128i*>(from) + k));
#else
  std::memcpy(to, from, bytes);
#endif
}

// Orders the streaming stores before the stores that follow (and so before the work is handed
// to another thread).
inline void stream_fence() {
#if XSIMD_WITH_SSE2
  _mm_sfence();
#endif
}

// Minimum and maximum of `count` floats (`values` aligned for a batch). No NaN may be among
// them; then the result does not depend on the order of the comparisons.
inline void min_max(const float* values, int count, float& lo, float& hi) {
  lo = values[0];
  hi = values[0];
  int i = 0;
  if (count >= kWidth) {
    Floats vlo = Floats::load_aligned(values), vhi = vlo;
    for (i = kWidth; i + kWidth <= count; i += kWidth) {
      const Floats v = Floats::load_aligned(values + i);
      vlo = xsimd::select(v < vlo, v, vlo);  // compare and blend: GCC 12 reports its own
      vhi = xsimd::select(v > vhi, v, vhi);  // AVX-512 min/max intrinsics as uninitialized
    }
    alignas(64) float lanes_lo[kWidth], lanes_hi[kWidth];
    vlo.store_aligned(lanes_lo);
    vhi.store_aligned(lanes_hi);
    for (int k = 0; k < kWidth; ++k) {
      lo = lanes_lo[k] < lo ? lanes_lo[k] : lo;
      hi = lanes_hi[k] > hi ? lanes_hi[k] : hi;
    }
  }
  for (; i < count; ++i) {
    lo = values[i] < lo ? values[i] : lo;
    hi = values[i] > hi ? values[i] : hi;
  }
}

}  // namespace tetray::render::simd
