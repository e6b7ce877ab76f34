// A 128-bit integer for exact sums of quantized terms (render/update/vertex_gradients.hpp):
// integer addition is associative, so such a sum does not depend on the order of its terms or
// on how they are split among ranks. GCC and Clang provide it; `__extension__` keeps
// -Wpedantic quiet about the non-standard type.
#pragma once

namespace tetray::render {

__extension__ typedef __int128 Int128;

}  // namespace tetray::render
