// What the writer draws on a scene's composited image (render/annotate): the scene's annotation
// config filled in with this step's number, simulated time and color range. Built on the writer
// rank only, and only for scenes that ask for annotations.
#pragma once

#include <span>
#include <string>

#include "adaptor/config/config.hpp"
#include "adaptor/output/step_record.hpp"
#include "render/annotate/annotate.hpp"
#include "render/scene/colormap.hpp"

namespace tetray {

// The caption: "<scene>   step <step>   t = <time>".
std::string caption_text(const std::string& scene, std::int64_t step, double time);

// One colormapped thing a scene drew this step (surfaces colored by a field, a clip cap, a
// volume's transfer function): its field's name, its colormap and the range it used.
struct ColorScale {
  std::string label;
  const render::Colormap* colormap = nullptr;
  double lo = 0, hi = 1;
};

// Empty when the scene asks for none; with `colorbar`, one bar per scale, in order.
render::Annotations annotations_for(const config::Scene& scene, const StepRecord& record,
                                    std::span<const ColorScale> scales);

}  // namespace tetray
