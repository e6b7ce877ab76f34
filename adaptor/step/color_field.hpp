// Coloring a surface by a second field (docs/config.md, color_by): the field's range on
// this rank, for an automatic colormap range (the values go to the renderer through
// render::load_color_field). Only scenes with color_by call these.
#pragma once

#include "render/parallel/global_reduce.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

render::ValueRange local_field_range(const FieldView& field);

// Makes a global data range usable by a colormap: non-empty and of positive width.
void usable_color_range(render::ValueRange& range);

}  // namespace tetray
