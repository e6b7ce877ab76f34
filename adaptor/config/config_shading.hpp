// The scene keys of the shading modalities (docs/config.md, Wald et al. 2007, §7), after
// validation: smooth or flat normals, the clip region and the lights. config_shading_parse.hpp
// reads them from the YAML.
#pragma once

#include <string>

#include "adaptor/config/config_colormap.hpp"
#include "render/scene/clip_region.hpp"
#include "render/scene/lights.hpp"

namespace tetray::config {

// A clip region's cap (Wald et al. 2007, §7): where it cuts the mesh, the cut shows `field`
// through a colormap (render/walk/clip_cap.hpp).
struct CapSpec {
  std::string field;  // empty: no cap
  std::string colormap_name = "viridis";
  ColorRange range{};
};

struct ShadingSpec {
  bool smooth = false;        // field-gradient normals interpolated at the hit; flat by default
  render::ClipRegion clip{};  // world coordinates; empty: nothing clipped
  CapSpec cap{};              // of the clip region
  render::Lights lights{};    // world coordinates; none: the headlight alone
  int max_layers = 4;         // transparent layers per pixel (render::TraceOptions::max_layers)
};

}  // namespace tetray::config
