// The solver's point arrays as the renderer reads them: non-owning views of float or double
// coordinates, displacements and field values, in the caller's point order.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetray::render {

enum class ScalarKind : std::uint8_t { f32, f64 };

struct PointSource {
  const void* xyz = nullptr;  // interleaved
  ScalarKind xyz_kind = ScalarKind::f64;
  const void* displacement = nullptr;  // optional, interleaved, added to xyz
  ScalarKind displacement_kind = ScalarKind::f64;
  std::size_t count = 0;
};

struct FieldSource {
  const void* values = nullptr;
  ScalarKind kind = ScalarKind::f64;
  std::size_t count = 0;
};

}  // namespace tetray::render
