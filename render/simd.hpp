// One SIMD vocabulary for the kernels (DESIGN §7): the few operations they need, over xsimd's
// widest float batch for the build target (AVX-512 where the CPU has it) and over plain float
// for the single-ray path. Both spellings do the same IEEE operations (no fused multiply-add),
// so a pixel gets bitwise the same result whatever the packet size.
#pragma once

#include <xsimd/xsimd.hpp>

#include <cstddef>
#include <cstdint>

namespace tetray::render::simd {

using Floats = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;
using Ints = xsimd::batch<std::int32_t>;
inline constexpr int kWidth = static_cast<int>(Floats::size);

// Four floats in one register: a Vertex (x, y, z, f) or one side of a 4D bound, so a bound
// grows by one min and one max per vertex (seed 000 §6.2).
using Float4 = xsimd::make_sized_batch_t<float, 4>;

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

inline Floats vmin(Floats a, Floats b) { return xsimd::min(a, b); }
inline float vmin(float a, float b) { return a < b ? a : b; }
inline Floats vmax(Floats a, Floats b) { return xsimd::max(a, b); }
inline float vmax(float a, float b) { return a > b ? a : b; }
inline Floats select(Mask m, Floats a, Floats b) { return xsimd::select(m, a, b); }
inline float select(bool m, float a, float b) { return m ? a : b; }
inline bool any(Mask m) { return xsimd::any(m); }
inline bool any(bool m) { return m; }

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

}  // namespace tetray::render::simd
