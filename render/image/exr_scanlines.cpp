// Scanline EXR files assembled here (exr_scanlines.hpp). The layout ("OpenEXR File Layout"):
// magic number and version, the header's attributes, a table of line-block offsets, then per
// block its first y, its byte count and its data. A block holds 1 line (none, RLE, ZIPS) or 16
// (ZIP); its uncompressed data is, line by line, each channel's values in the channels'
// alphabetical order (A, B, G, R, Z), little-endian. RLE and ZIP first split the block's bytes
// into the even-numbered and the odd-numbered ones, then replace each byte by its difference to
// the one before plus 128 (OpenEXR's ImfRleCompressor.cpp and ImfZip.cpp); a block that does not
// get smaller is stored uncompressed, as OpenEXR's reader expects.
#include "render/image/exr_scanlines.hpp"

#include <emmintrin.h>
#include <libdeflate.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <string_view>

#include "render/image/deflate_compressor.hpp"

namespace tetray::render {
namespace {

constexpr int kLinesPerGroup = 16;         // the lines of one parallel task: ZIP's block
constexpr std::size_t kMaxRun = 128;       // the longest run or literal one RLE code describes
constexpr std::size_t kMinRun = 3;         // shorter runs are cheaper as literals
constexpr int kBytesPerPixel = 4 * 2 + 4;  // four halves and a float

int lines_per_block(ExrCompression compression) {
  return compression == ExrCompression::zip ? kLinesPerGroup : 1;
}

// ------------------------------------------------------------------------------ half conversion

// Four floats to halves with IEEE round to nearest even, as Imath's half(float) (whose F16C form
// the render libraries cannot use: only the ISA variants may hold AVX encodings, and F16C has no
// other), in SSE2: a magnitude from 2^16 on becomes infinity or a quiet NaN, one below 2^-14 a
// subnormal rounded by a float addition that aligns its bits, any other gets its exponent
// rebiased and 13 mantissa bits rounded off (F. Giesen, "float->half variants", 2013). Each
// lane holds the half, sign-extended, so that packing pairs to 16 bits keeps it.
__m128i halves4(__m128 value) {
  const __m128 sign =
      _mm_and_ps(value, _mm_castsi128_ps(_mm_set1_epi32(std::numeric_limits<std::int32_t>::min())));
  const __m128 magnitude = _mm_xor_ps(value, sign);
  const __m128i bits = _mm_castps_si128(magnitude);
  const __m128i subnormal_magic = _mm_set1_epi32((127 - 15 + 23 - 10 + 1) << 23);

  const __m128i nan = _mm_castps_si128(_mm_cmpunord_ps(magnitude, magnitude));
  const __m128i special = _mm_or_si128(_mm_and_si128(nan, _mm_set1_epi32(0x200)),
                                       _mm_set1_epi32(0x7c00));  // infinity or quiet NaN
  const __m128i regular = _mm_cmpgt_epi32(_mm_set1_epi32((127 + 16) << 23), bits);
  const __m128i subnormal = _mm_cmpgt_epi32(_mm_set1_epi32((127 - 14) << 23), bits);

  const __m128i small = _mm_sub_epi32(
      _mm_castps_si128(_mm_add_ps(magnitude, _mm_castsi128_ps(subnormal_magic))), subnormal_magic);
  const __m128i odd = _mm_srai_epi32(_mm_slli_epi32(bits, 31 - 13), 31);  // -1 where LSB kept is 1
  const __m128i normal = _mm_srli_epi32(
      _mm_sub_epi32(_mm_add_epi32(bits, _mm_set1_epi32(0xfff - ((127 - 15) << 23))), odd), 13);

  const __m128i finite =
      _mm_or_si128(_mm_and_si128(subnormal, small), _mm_andnot_si128(subnormal, normal));
  const __m128i half =
      _mm_or_si128(_mm_and_si128(regular, finite), _mm_andnot_si128(regular, special));
  return _mm_or_si128(half, _mm_srai_epi32(_mm_castps_si128(sign), 16));
}

// `n` (a multiple of 4) floats to halves.
void to_halves(const float* in, std::size_t n, std::uint16_t* out) {
  std::size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    const __m128i low = halves4(_mm_loadu_ps(in + k)), high = halves4(_mm_loadu_ps(in + k + 4));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + k), _mm_packs_epi32(low, high));
  }
  if (k < n) {
    const __m128i last = _mm_packs_epi32(halves4(_mm_loadu_ps(in + k)), _mm_setzero_si128());
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + k), last);
  }
}

// ---------------------------------------------------------------------------- line block bytes

// Line `y`'s bytes of the block split into even- and odd-numbered ones, at `even` and `odd`
// (6 x width bytes each). Every channel's run of values has an even length, so a half's low
// byte is even and its high byte odd; a float's bytes go even, odd, even, odd.
void split_line(const Framebuffer& image, int y, std::uint16_t* halves, std::uint8_t* even,
                std::uint8_t* odd) {
  const std::size_t w = static_cast<std::size_t>(image.width);
  to_halves(&image.rgba[4 * w * static_cast<std::size_t>(y)], 4 * w, halves);
  for (std::size_t q = 0; q < 4; ++q) {  // A, B, G, R: the framebuffer's channels 3, 2, 1, 0
    const std::uint16_t* channel = halves + (3 - q);
    for (std::size_t x = 0; x < w; ++x) {
      const std::uint16_t h = channel[4 * x];
      even[q * w + x] = static_cast<std::uint8_t>(h);
      odd[q * w + x] = static_cast<std::uint8_t>(h >> 8);
    }
  }
  const float* depth = &image.depth[w * static_cast<std::size_t>(y)];
  for (std::size_t x = 0; x < w; ++x) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(depth[x]);
    even[4 * w + 2 * x] = static_cast<std::uint8_t>(bits);
    even[4 * w + 2 * x + 1] = static_cast<std::uint8_t>(bits >> 16);
    odd[4 * w + 2 * x] = static_cast<std::uint8_t>(bits >> 8);
    odd[4 * w + 2 * x + 1] = static_cast<std::uint8_t>(bits >> 24);
  }
}

// The uncompressed block back from its split halves.
void interleave(std::span<const std::uint8_t> split, std::uint8_t* out) {
  const std::size_t half = split.size() / 2;
  for (std::size_t k = 0; k < half; ++k) {
    out[2 * k] = split[k];
    out[2 * k + 1] = split[half + k];
  }
}

// Each byte as its difference to the one before, plus 128; the first stays.
void predict(std::span<const std::uint8_t> in, std::uint8_t* out) {
  out[0] = in[0];
  for (std::size_t k = 1; k < in.size(); ++k) {
    out[k] = static_cast<std::uint8_t>(in[k] - in[k - 1] + 128);
  }
}

// ------------------------------------------------------------------------------------------ RLE

// RLE scans 16 bytes at a time (SSE2, which every x86-64 CPU has, as halves4 uses): the run-length
// stage is most of an RLE file's encoding time, and a rendered frame is mostly short literals
// between runs.
std::uint32_t equal_bytes(const std::uint8_t* a, __m128i b) {
  const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a));
  return static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, b)));
}

// The first position p >= `from` that starts kMinRun equal bytes, or in.size() if none does.
std::size_t next_run(std::span<const std::uint8_t> in, std::size_t from) {
  static_assert(kMinRun == 3);
  const std::size_t n = in.size();
  std::size_t p = from;
  for (; p + 18 <= n; p += 16) {
    const __m128i next = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&in[p + 1]));
    const std::uint32_t starts = equal_bytes(&in[p], next) & equal_bytes(&in[p + 2], next);
    if (starts != 0) return p + static_cast<std::size_t>(std::countr_zero(starts));
  }
  for (; p + 2 < n; ++p) {
    if (in[p] == in[p + 1] && in[p] == in[p + 2]) return p;
  }
  return n;
}

// How many bytes from `at` equal in[at], at most kMaxRun.
std::size_t run_at(std::span<const std::uint8_t> in, std::size_t at) {
  const std::size_t limit = std::min(in.size() - at, kMaxRun);
  const __m128i value = _mm_set1_epi8(static_cast<char>(in[at]));
  std::size_t run = 0;
  for (; run + 16 <= limit; run += 16) {
    const std::uint32_t equal = equal_bytes(&in[at + run], value);
    if (equal != 0xffff) return run + static_cast<std::size_t>(std::countr_one(equal));
  }
  while (run < limit && in[at + run] == in[at]) ++run;
  return run;
}

// OpenEXR's run-length code (ImfRle.cpp): a run of n >= 3 equal bytes as the byte n - 1 and the
// value; n <= 128 other bytes as the byte -n and the bytes themselves. Returns the byte count
// written at `out`, which has room for in.size() + in.size() / kMaxRun + 1 bytes.
std::size_t rle(std::span<const std::uint8_t> in, std::uint8_t* out) {
  std::uint8_t* const start = out;
  std::size_t literal = 0;  // the first byte not yet written
  while (literal < in.size()) {
    const std::size_t run = next_run(in, literal);
    for (std::size_t count; literal < run; literal += count) {
      count = std::min(run - literal, kMaxRun);
      *out++ = static_cast<std::uint8_t>(-static_cast<int>(count));
      out = std::copy_n(&in[literal], count, out);
    }
    if (run == in.size()) break;
    const std::size_t length = run_at(in, run);
    *out++ = static_cast<std::uint8_t>(length - 1);
    *out++ = in[run];
    literal = run + length;
  }
  return static_cast<std::size_t>(out - start);
}

// --------------------------------------------------------------------------------- line blocks

// One thread's buffers, reused from group to group.
struct Scratch {
  std::vector<std::uint16_t> halves;
  std::vector<std::uint8_t> split, predicted, packed;
  DeflateCompressor compressor;  // made at the first ZIP block
};

void put_u32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

void put_u64_at(unsigned char* at, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) at[k] = static_cast<unsigned char>(v >> (8 * k));
}

std::uint32_t u32_at(const unsigned char* at) {
  return std::uint32_t{at[0]} | std::uint32_t{at[1]} << 8 | std::uint32_t{at[2]} << 16 |
         std::uint32_t{at[3]} << 24;
}

// The compressed data of one block, or empty where it would not be smaller than `in`.
std::span<const std::uint8_t> compressed(std::span<const std::uint8_t> in,
                                         ExrCompression compression, Scratch& s) {
  if (compression == ExrCompression::none) return {};
  s.predicted.resize(in.size());
  predict(in, s.predicted.data());
  s.packed.resize(in.size() + in.size() / kMaxRun + 1);
  std::size_t size = 0;
  if (compression == ExrCompression::rle) {
    size = rle(s.predicted, s.packed.data());
  } else {
    // zlib, as OpenEXR's ZIP and ZIPS (at the fastest level, exr_encode.cpp); 0 when it does
    // not fit in fewer bytes than the block.
    if (!s.compressor) s.compressor = make_deflate_compressor(1);
    size = libdeflate_zlib_compress(s.compressor.get(), s.predicted.data(), in.size(),
                                    s.packed.data(), in.size() - 1);
  }
  if (size == 0 || size >= in.size()) return {};
  return {s.packed.data(), size};
}

// Appends the line block of lines first..last - 1: its y, its byte count and its data.
void put_block(const Framebuffer& image, int first, int last, ExrCompression compression,
               Scratch& s, std::vector<unsigned char>& out) {
  const std::size_t w = static_cast<std::size_t>(image.width);
  const std::size_t half = 6 * w * static_cast<std::size_t>(last - first);
  s.halves.resize(4 * w);
  s.split.resize(2 * half);
  for (int y = first; y < last; ++y) {
    const std::size_t at = 6 * w * static_cast<std::size_t>(y - first);
    split_line(image, y, s.halves.data(), &s.split[at], &s.split[half + at]);
  }
  const std::span<const std::uint8_t> data = compressed(s.split, compression, s);
  put_u32(out, static_cast<std::uint32_t>(first));
  put_u32(out, static_cast<std::uint32_t>(data.empty() ? s.split.size() : data.size()));
  if (data.empty()) {
    const std::size_t at = out.size();
    out.resize(at + s.split.size());
    interleave(s.split, &out[at]);
  } else {
    out.insert(out.end(), data.begin(), data.end());
  }
}

// ----------------------------------------------------------------------------------- header

void put_attribute(std::vector<unsigned char>& out, std::string_view name, std::string_view type,
                   std::span<const unsigned char> value) {
  out.insert(out.end(), name.begin(), name.end());
  out.push_back(0);
  out.insert(out.end(), type.begin(), type.end());
  out.push_back(0);
  put_u32(out, static_cast<std::uint32_t>(value.size()));
  out.insert(out.end(), value.begin(), value.end());
}

std::vector<unsigned char> u32s(std::initializer_list<std::uint32_t> values) {
  std::vector<unsigned char> bytes;
  for (std::uint32_t v : values) put_u32(bytes, v);
  return bytes;
}

// The attributes every scanline file has (those OpenEXR's Header(width, height) sets).
void put_header(std::vector<unsigned char>& out, int width, int height,
                ExrCompression compression) {
  out.insert(out.end(), {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0});  // magic; version 2, scanline
  std::vector<unsigned char> channels;
  constexpr std::uint32_t kHalf = 1, kFloat = 2;
  for (const auto& [name, type] :
       {std::pair{'A', kHalf}, {'B', kHalf}, {'G', kHalf}, {'R', kHalf}, {'Z', kFloat}}) {
    channels.insert(channels.end(), {static_cast<unsigned char>(name), 0});
    const std::vector<unsigned char> fields = u32s({type, 0, 1, 1});  // pLinear 0, sampling 1 1
    channels.insert(channels.end(), fields.begin(), fields.end());
  }
  channels.push_back(0);
  put_attribute(out, "channels", "chlist", channels);
  const unsigned char compression_byte[] = {static_cast<unsigned char>(compression)};
  put_attribute(out, "compression", "compression", compression_byte);
  const std::vector<unsigned char> window =
      u32s({0, 0, static_cast<std::uint32_t>(width - 1), static_cast<std::uint32_t>(height - 1)});
  put_attribute(out, "dataWindow", "box2i", window);
  put_attribute(out, "displayWindow", "box2i", window);
  const unsigned char increasing_y[] = {0};
  put_attribute(out, "lineOrder", "lineOrder", increasing_y);
  const std::vector<unsigned char> one = u32s({std::bit_cast<std::uint32_t>(1.0f)});
  put_attribute(out, "pixelAspectRatio", "float", one);
  put_attribute(out, "screenWindowCenter", "v2f", u32s({0, 0}));
  put_attribute(out, "screenWindowWidth", "float", one);
  out.push_back(0);  // end of the header
}

}  // namespace

bool exr_scanlines_write(ExrCompression compression) {
  return compression == ExrCompression::none || compression == ExrCompression::rle ||
         compression == ExrCompression::zips || compression == ExrCompression::zip;
}

void encode_exr_scanlines(const Framebuffer& image, ExrCompression compression,
                          std::vector<unsigned char>& bytes) {
  const int lines = lines_per_block(compression);
  const std::size_t blocks = static_cast<std::size_t>((image.height + lines - 1) / lines);
  put_header(bytes, image.width, image.height, compression);
  const std::size_t table = bytes.size();
  // Room for the offset table and every block uncompressed (the most a block takes): the bytes
  // never move, and the pages never written are never touched.
  bytes.reserve(table + 8 * blocks +
                static_cast<std::size_t>(image.height) *
                    (kBytesPerPixel * static_cast<std::size_t>(image.width) + 8));
  bytes.resize(table + 8 * blocks);

  // The groups of lines are compressed a batch at a time into buffers that the next batch
  // reuses, then appended in order: new memory (and its page faults, which cost about as much as
  // compressing) only for the file itself and one batch, not for a second copy of the file.
  const int groups = (image.height + kLinesPerGroup - 1) / kLinesPerGroup;
  const int batch = std::min(groups, 4 * tbb::this_task_arena::max_concurrency());
  std::vector<std::vector<unsigned char>> staged(static_cast<std::size_t>(batch));
  tbb::enumerable_thread_specific<Scratch> scratch;
  std::size_t block = 0;
  for (int first_group = 0; first_group < groups; first_group += batch) {
    const int last_group = std::min(groups, first_group + batch);
    tbb::parallel_for(first_group, last_group, [&](int g) {
      std::vector<unsigned char>& out = staged[static_cast<std::size_t>(g - first_group)];
      out.clear();
      const int end = std::min(image.height, (g + 1) * kLinesPerGroup);
      for (int first = g * kLinesPerGroup; first < end; first += lines) {
        put_block(image, first, std::min(end, first + lines), compression, scratch.local(), out);
      }
    });
    for (int g = first_group; g < last_group; ++g) {
      const std::vector<unsigned char>& out = staged[static_cast<std::size_t>(g - first_group)];
      // Each block: y, byte count, data (put_block).
      for (std::size_t at = 0; at < out.size(); at += 8 + u32_at(&out[at + 4])) {
        put_u64_at(&bytes[table + 8 * block++], bytes.size() + at);
      }
      bytes.insert(bytes.end(), out.begin(), out.end());
    }
  }
}

}  // namespace tetray::render
