// Coloring a surface by a second field (DESIGN §4 color_by): the field's range on this rank
// (for an automatic colormap range) and its values as the renderer's per-vertex floats. Only
// scenes with color_by call these.
#pragma once

#include <vector>

#include "render/global_reduce.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

render::ValueRange local_field_range(const FieldView& field);
void convert_color_field(const FieldView& field, std::vector<float>& out);

// Makes a global data range usable by a colormap: non-empty and of positive width.
void usable_color_range(render::ValueRange& range);

}  // namespace tetray
