// The colormaps of the config's `colormap:` key. Tables are the published sRGB values; they are
// decoded to linear once, because the framebuffer is linear and the PNG writer encodes to sRGB
// again, so a surface colored at s shows the published color.
#include "render/scene/colormap.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "render/core/srgb.hpp"

namespace tetray::render {
namespace {

// Viridis (van der Walt and Smith, matplotlib, CC0): every 5th entry of the published
// 256-entry table (entries 0, 5, ..., 255), so 52 evenly spaced stops.
constexpr float kViridisSrgb[][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.273809f, 0.031497f, 0.358853f},
    {0.278791f, 0.062145f, 0.386592f}, {0.281924f, 0.089666f, 0.412415f},
    {0.283197f, 0.115680f, 0.436115f}, {0.282623f, 0.140926f, 0.457517f},
    {0.280255f, 0.165693f, 0.476498f}, {0.276194f, 0.190074f, 0.493001f},
    {0.270595f, 0.214069f, 0.507052f}, {0.263663f, 0.237631f, 0.518762f},
    {0.255645f, 0.260703f, 0.528312f}, {0.246811f, 0.283237f, 0.535941f},
    {0.237441f, 0.305202f, 0.541921f}, {0.227802f, 0.326594f, 0.546532f},
    {0.218130f, 0.347432f, 0.550038f}, {0.208623f, 0.367752f, 0.552675f},
    {0.199430f, 0.387607f, 0.554642f}, {0.190631f, 0.407061f, 0.556089f},
    {0.182256f, 0.426184f, 0.557120f}, {0.174274f, 0.445044f, 0.557792f},
    {0.166617f, 0.463708f, 0.558119f}, {0.159194f, 0.482237f, 0.558073f},
    {0.151918f, 0.500685f, 0.557587f}, {0.144759f, 0.519093f, 0.556572f},
    {0.137770f, 0.537492f, 0.554906f}, {0.131172f, 0.555899f, 0.552459f},
    {0.125394f, 0.574318f, 0.549086f}, {0.121148f, 0.592739f, 0.544641f},
    {0.119423f, 0.611141f, 0.538982f}, {0.121380f, 0.629492f, 0.531973f},
    {0.128087f, 0.647749f, 0.523491f}, {0.140210f, 0.665859f, 0.513427f},
    {0.157851f, 0.683765f, 0.501686f}, {0.180653f, 0.701402f, 0.488189f},
    {0.208030f, 0.718701f, 0.472873f}, {0.239374f, 0.735588f, 0.455688f},
    {0.274149f, 0.751988f, 0.436601f}, {0.311925f, 0.767822f, 0.415586f},
    {0.352360f, 0.783011f, 0.392636f}, {0.395174f, 0.797475f, 0.367757f},
    {0.440137f, 0.811138f, 0.340967f}, {0.487026f, 0.823929f, 0.312321f},
    {0.535621f, 0.835785f, 0.281908f}, {0.585678f, 0.846661f, 0.249897f},
    {0.636902f, 0.856542f, 0.216620f}, {0.688944f, 0.865448f, 0.182725f},
    {0.741388f, 0.873449f, 0.149561f}, {0.793760f, 0.880678f, 0.120005f},
    {0.845561f, 0.887322f, 0.099702f}, {0.896320f, 0.893616f, 0.096335f},
    {0.945636f, 0.899815f, 0.112838f}, {0.993248f, 0.906157f, 0.143936f},
};

// Moreland's smooth cool-warm diverging map ("Diverging Color Maps for Scientific
// Visualization", 2009), his published 33-entry table.
constexpr float kCoolWarmSrgb[][3] = {
    {0.2298057f, 0.298717966f, 0.753683153f},   {0.26623388f, 0.353094838f, 0.801466763f},
    {0.30386891f, 0.406535296f, 0.84495867f},   {0.342804478f, 0.458757618f, 0.883725899f},
    {0.38301334f, 0.50941904f, 0.917387822f},   {0.424369608f, 0.558148092f, 0.945619588f},
    {0.46666708f, 0.604562568f, 0.968154911f},  {0.509635204f, 0.648280772f, 0.98478814f},
    {0.552953156f, 0.688929332f, 0.995375608f}, {0.596262162f, 0.726149107f, 0.999836203f},
    {0.639176211f, 0.759599947f, 0.998151185f}, {0.681291281f, 0.788964712f, 0.990363227f},
    {0.722193294f, 0.813952739f, 0.976574709f}, {0.761464949f, 0.834302879f, 0.956945269f},
    {0.798691636f, 0.849786142f, 0.931688648f}, {0.833466556f, 0.860207984f, 0.901068838f},
    {0.865395197f, 0.86541021f, 0.865395561f},  {0.897787179f, 0.848937047f, 0.820880546f},
    {0.924127593f, 0.827384882f, 0.774508472f}, {0.944468518f, 0.800927443f, 0.726736146f},
    {0.958852946f, 0.769767752f, 0.678007945f}, {0.96732803f, 0.734132809f, 0.628751763f},
    {0.969954137f, 0.694266682f, 0.579375448f}, {0.966811177f, 0.650421156f, 0.530263762f},
    {0.958003065f, 0.602842431f, 0.481775914f}, {0.943660866f, 0.551750968f, 0.434243684f},
    {0.923944917f, 0.49730856f, 0.387970225f},  {0.89904617f, 0.439559467f, 0.343229596f},
    {0.869186849f, 0.378313092f, 0.300267182f}, {0.834620542f, 0.312874446f, 0.259301199f},
    {0.795631745f, 0.24128379f, 0.220525627f},  {0.752534934f, 0.157246067f, 0.184115123f},
    {0.705673158f, 0.01555616f, 0.150232812f},
};

Colormap decoded(std::span<const float[3]> srgb_stops) {
  Colormap map;
  map.stops.reserve(3 * srgb_stops.size());
  for (const auto& stop : srgb_stops) {
    for (float v : stop) map.stops.push_back(static_cast<float>(srgb_decode(v)));
  }
  return map;
}

// Gray levels evenly spaced in sRGB (perceptually even steps), black to white.
Colormap grayscale() {
  constexpr int kStops = 33;
  Colormap map;
  for (int k = 0; k < kStops; ++k) {
    const auto level = static_cast<float>(srgb_decode(k / double(kStops - 1)));
    map.stops.insert(map.stops.end(), {level, level, level});
  }
  return map;
}

}  // namespace

void Colormap::lookup(float s, float rgb[3]) const {
  const std::size_t count = stops.size() / 3;
  const float position = std::clamp(std::isnan(s) ? 0.0f : s, 0.0f, 1.0f) * float(count - 1);
  const std::size_t lower = std::min(static_cast<std::size_t>(position), count - 2);
  const float weight = position - float(lower);
  for (int c = 0; c < 3; ++c) {
    const float a = stops[3 * lower + c];
    const float b = stops[3 * (lower + 1) + c];
    rgb[c] = a + weight * (b - a);
  }
}

const Colormap* find_colormap(std::string_view name) {
  static const Colormap viridis = decoded(kViridisSrgb);
  static const Colormap coolwarm = decoded(kCoolWarmSrgb);
  static const Colormap gray = grayscale();
  if (name == "viridis") return &viridis;
  if (name == "coolwarm") return &coolwarm;
  if (name == "grayscale") return &gray;
  return nullptr;
}

}  // namespace tetray::render
