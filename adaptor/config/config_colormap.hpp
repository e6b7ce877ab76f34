// The value range every colormapped thing of a scene has (color_by, a volume's transfer
// function, a clip cap), after validation; config_colormap_parse.hpp reads it from the YAML.
#pragma once

namespace tetray::config {

struct ColorRange {
  bool automatic = true;  // global min/max of the colored field at each rendered step
  float lo = 0, hi = 1;
};

}  // namespace tetray::config
