#include "adaptor/output/annotations.hpp"

namespace tetray {
namespace {

// Samples enough that linear interpolation between them stays within half an 8-bit step of
// the colormap's own piecewise-linear stops.
constexpr int kColorbarSamples = 256;

std::vector<float> sample_colormap(const render::Colormap& colormap) {
  std::vector<float> colors(3 * kColorbarSamples);
  for (int k = 0; k < kColorbarSamples; ++k) {
    colormap.lookup(static_cast<float>(k) / (kColorbarSamples - 1), &colors[3 * k]);
  }
  return colors;
}

}  // namespace

std::string caption_text(const std::string& scene, std::int64_t step, double time) {
  return scene + "   step " + std::to_string(step) + "   t = " + time_text(time);
}

render::Annotations annotations_for(const config::Scene& scene, const StepRecord& record,
                                    std::span<const ColorScale> scales) {
  const config::Annotations& spec = scene.annotations;
  render::Annotations a;
  if (!spec.font) return a;
  a.font = spec.font;
  a.title = spec.title;
  if (spec.time) a.caption = caption_text(scene.name, record.step, record.time);
  for (const ColorScale& scale : scales) {
    if (!spec.colorbar) break;
    a.colorbars.push_back({scale.label, scale.lo, scale.hi, sample_colormap(*scale.colormap)});
  }
  return a;
}

}  // namespace tetray
