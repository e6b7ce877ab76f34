// What the writer draws on a scene's composited image (render/annotate): the scene's annotation
// config filled in with this step's number, simulated time and color range. Built on the writer
// rank only, and only for scenes that ask for annotations.
#pragma once

#include "config.hpp"
#include "render/annotate/annotate.hpp"
#include "render/trace/colormap.hpp"
#include "step_record.hpp"

namespace tetray {

// The caption: "<scene>   step <step>   t = <time>".
std::string caption_text(const std::string& scene, std::int64_t step, double time);

// Empty when the scene asks for none. `colormap` and [lo, hi] are the ones the surfaces were
// colored with (null without color_by).
render::Annotations annotations_for(const config::Scene& scene, const StepRecord& record,
                                    const render::Colormap* colormap, float lo, float hi);

}  // namespace tetray
