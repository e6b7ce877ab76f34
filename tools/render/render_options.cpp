#include "tools/render/render_options.hpp"

#include "render/core/value_bounds.hpp"
#include "render/image/image_write.hpp"
#include "render/scene/camera.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace tetray::tools {
namespace {

constexpr int kMaxImageSide = 16384;

std::optional<double> parse_number(std::string_view text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// "X,Y,Z" -> three finite numbers.
std::optional<render::Vec3d> parse_vec3(const std::string& text) {
  render::Vec3d v;
  std::string_view rest = text;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t comma = axis < 2 ? rest.find(',') : rest.size();
    if (comma == std::string_view::npos) return std::nullopt;
    const std::optional<double> value = parse_number(rest.substr(0, comma));
    if (!value) return std::nullopt;
    v[axis] = *value;
    rest.remove_prefix(std::min(rest.size(), comma + 1));
  }
  return v;
}

// "WxH" -> two sides in [1, kMaxImageSide].
std::optional<std::pair<int, int>> parse_size(const std::string& text) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  const std::optional<double> w = parse_number(std::string_view(text).substr(0, x));
  const std::optional<double> h = parse_number(std::string_view(text).substr(x + 1));
  auto valid = [](std::optional<double> side) {
    return side && *side >= 1 && *side <= kMaxImageSide && std::floor(*side) == *side;
  };
  if (!valid(w) || !valid(h)) return std::nullopt;
  return std::pair{static_cast<int>(*w), static_cast<int>(*h)};
}

std::string text_of(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

CLI::Validator vec3_format() {
  return CLI::Validator(
      [](std::string& text) { return parse_vec3(text) ? "" : "expected X,Y,Z (three numbers)"; },
      "X,Y,Z");
}

CLI::Validator size_format() {
  return CLI::Validator(
      [](std::string& text) {
        return parse_size(text)
                   ? ""
                   : "expected WxH with whole sides in 1.." + std::to_string(kMaxImageSide);
      },
      "WxH");
}

// A finite number in [lo, hi]; CLI::Range lets NaN through (every comparison with it is false).
CLI::Validator finite_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        const std::optional<double> value = parse_number(text);
        return value && *value >= lo && *value <= hi
                   ? std::string()
                   : "expected a number in [" + text_of(lo) + ", " + text_of(hi) + "]";
      },
      "NUMBER");
}

CLI::Validator image_extension() {
  return CLI::Validator(
      [](std::string& path) {
        return render::image_format_of(path) ? "" : "the output must end in .exr or .png";
      },
      "OUT.exr|OUT.png");
}

// Options given as text and converted once the whole command line has been checked.
struct OptionTexts {
  std::string eye, look_at, up, size = "1024x1024";
};

void declare_options(CLI::App& app, RenderOptions& options, OptionTexts& texts) {
  app.add_option("file", options.input, "input grid (.vtu or .pvtu)")->required();
  app.add_option("--field", options.field, "point field to draw isosurfaces of")->required();
  app.add_option("--iso", options.isovalues, "isovalue (repeat for more surfaces, at most 16)")
      ->required()
      ->allow_extra_args(false);
  app.add_option("--eye", texts.eye, "camera position (default: fit the mesh bounds)")
      ->check(vec3_format());
  app.add_option("--look-at", texts.look_at, "point the camera looks at (default: mesh center)")
      ->check(vec3_format())
      ->needs("--eye");
  app.add_option("--up", texts.up, "camera up direction (default: +y)")->check(vec3_format());
  app.add_option("--fov", options.fov_deg, "vertical field of view in degrees")
      ->check(finite_in(render::kMinFovDeg, render::kMaxFovDeg))
      ->capture_default_str();
  app.add_option("--size", texts.size, "image size")->check(size_format())->capture_default_str();
  app.add_option("--threads", options.threads, "worker threads (default: every core)")
      ->check(CLI::Range(1, 1024));
  app.add_option("-o,--output", options.output, "output image (.exr or .png)")
      ->required()
      ->check(image_extension());
}

// Throws CLI11's ValidationError, so that the message looks like every other option error.
void check_isovalues(const std::vector<double>& isovalues) {
  if (isovalues.size() > static_cast<std::size_t>(render::kMaxIsovalues)) {
    throw CLI::ValidationError("--iso", "at most " + std::to_string(render::kMaxIsovalues) +
                                            " isovalues, got " + std::to_string(isovalues.size()));
  }
  // No field value beyond kMaxFieldValue passes the mesh check, so no larger isovalue can be
  // drawn; the adaptor's config refuses one too.
  const auto drawable = [](double v) { return std::abs(v) <= render::kMaxFieldValue; };
  if (!std::all_of(isovalues.begin(), isovalues.end(), drawable)) {
    throw CLI::ValidationError("--iso", "isovalues must be finite numbers within +-1e30");
  }
}

// The texts passed their validators, so every conversion here succeeds.
void apply_texts(const OptionTexts& texts, RenderOptions& options) {
  if (!texts.eye.empty()) options.eye = parse_vec3(texts.eye);
  if (!texts.look_at.empty()) options.look_at = parse_vec3(texts.look_at);
  // At any scale, as the config takes it: [1e-300, 1e-300, 0] is the diagonal of x and y.
  if (!texts.up.empty()) options.up = render::unit_direction(*parse_vec3(texts.up));
  std::tie(options.width, options.height) = *parse_size(texts.size);
}

}  // namespace

std::optional<int> parse_render_options(int argc, char** argv, RenderOptions& options) {
  CLI::App app{"Ray-trace isosurfaces of a point field on a VTK grid of tets to an EXR or PNG."};
  OptionTexts texts;
  declare_options(app, options, texts);
  try {
    app.parse(argc, argv);
    check_isovalues(options.isovalues);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;  // README: 1 on a usage error, 0 for --help
  }
  apply_texts(texts, options);
  return std::nullopt;
}

}  // namespace tetray::tools
