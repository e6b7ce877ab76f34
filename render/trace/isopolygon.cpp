#include "render/trace/isopolygon.hpp"

namespace tetray::render {
namespace {

// Builds the marching-tetrahedra table: the lone vertex of a 1-3 split gives a triangle of its
// three edges (the first listed again as the fourth); a 2-2 split {a0, a1} | {b0, b1} gives the
// quad a0b0, a0b1, a1b1, a1b0, whose consecutive vertices share a tet face.
constexpr std::array<IsoCase, 16> make_cases() {
  std::array<IsoCase, 16> table{};
  for (int c = 0; c < 16; ++c) {
    int above[4], below[4], na = 0, nb = 0;
    for (int i = 0; i < 4; ++i) {
      if (c & (1 << i)) {
        above[na++] = i;
      } else {
        below[nb++] = i;
      }
    }
    IsoCase& entry = table[c];
    if (na == 0 || nb == 0) continue;
    if (na == 1 || nb == 1) {
      const int lone = na == 1 ? above[0] : below[0];
      const int* others = na == 1 ? below : above;
      entry.vertex_count = 3;
      for (int k = 0; k < 4; ++k) {
        entry.ends[0][k] = lone;
        entry.ends[1][k] = others[k % 3];
      }
      continue;
    }
    entry.vertex_count = 4;
    const int order[4][2] = {
        {above[0], below[0]}, {above[0], below[1]}, {above[1], below[1]}, {above[1], below[0]}};
    for (int k = 0; k < 4; ++k) {
      entry.ends[0][k] = order[k][0];
      entry.ends[1][k] = order[k][1];
    }
  }
  return table;
}

constexpr std::array<IsoCase, 16> kCases = make_cases();

}  // namespace

const std::array<IsoCase, 16>& iso_cases() { return kCases; }

}  // namespace tetray::render
