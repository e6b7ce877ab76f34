#include "minisolver/log_log_plot.hpp"

#include <algorithm>
#include <cmath>

#include "minisolver/raster.hpp"

namespace minisolver {
namespace {

constexpr int kWidth = 720, kHeight = 480;
constexpr int kLeft = 80, kRight = 20, kTop = 40, kBottom = 60;
const Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kGrid{220, 220, 220};
const Rgb kPalette[] = {
    {31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {148, 103, 189}, {255, 127, 14}};

// Whole decades covering [lo, hi] of the data.
struct DecadeRange {
  int first = 0, last = 1;

  static DecadeRange of(double lo, double hi) {
    DecadeRange r{static_cast<int>(std::floor(std::log10(lo))),
                  static_cast<int>(std::ceil(std::log10(hi)))};
    if (r.last <= r.first) r.last = r.first + 1;
    return r;
  }
  double fraction(double v) const { return (std::log10(v) - first) / (last - first); }
};

struct Frame {
  DecadeRange x, y;

  int px(double v) const {
    return kLeft + static_cast<int>(std::lround(x.fraction(v) * (kWidth - kLeft - kRight)));
  }
  int py(double v) const {
    return kHeight - kBottom -
           static_cast<int>(std::lround(y.fraction(v) * (kHeight - kTop - kBottom)));
  }
};

Frame frame_of(const std::vector<PlotSeries>& series) {
  double x_lo = HUGE_VAL, x_hi = 0, y_lo = HUGE_VAL, y_hi = 0;
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points) {
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
      y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    }
  return {DecadeRange::of(x_lo, x_hi), DecadeRange::of(y_lo, y_hi)};
}

std::string decade_label(int exponent) { return "1E" + std::to_string(exponent); }

void draw_axes(Raster& r, const Frame& f, const std::string& x_label, const std::string& y_label) {
  const int x0 = kLeft, x1 = kWidth - kRight, y0 = kTop, y1 = kHeight - kBottom;
  for (int e = f.x.first; e <= f.x.last; ++e) {
    const int x = f.px(std::pow(10.0, e));
    r.line(x, y0, x, y1, kGrid);
    r.line(x, y1, x, y1 + 6, kBlack);
    const std::string label = decade_label(e);
    r.text(x - Raster::text_width(label) / 2, y1 + 12, label, kBlack);
  }
  for (int e = f.y.first; e <= f.y.last; ++e) {
    const int y = f.py(std::pow(10.0, e));
    r.line(x0, y, x1, y, kGrid);
    r.line(x0 - 6, y, x0, y, kBlack);
    const std::string label = decade_label(e);
    r.text(x0 - 10 - Raster::text_width(label), y - 5, label, kBlack);
  }
  r.line(x0, y1, x1, y1, kBlack, 2);
  r.line(x0, y0, x0, y1, kBlack, 2);
  r.text((x0 + x1 - Raster::text_width(x_label)) / 2, kHeight - 22, x_label, kBlack);
  r.text(10, 12, y_label, kBlack);
}

void draw_series(Raster& r, const Frame& f, const PlotSeries& s, Rgb color) {
  for (std::size_t i = 1; i < s.points.size(); ++i)
    r.line(f.px(s.points[i - 1].first), f.py(s.points[i - 1].second), f.px(s.points[i].first),
           f.py(s.points[i].second), color, 2);
  for (const auto& [x, y] : s.points)
    r.fill_rect(f.px(x) - 4, f.py(y) - 4, f.px(x) + 4, f.py(y) + 4, color);
}

void draw_legend(Raster& r, const std::vector<PlotSeries>& series) {
  int y = kTop + 10;
  for (std::size_t i = 0; i < series.size(); ++i, y += 20) {
    const Rgb color = kPalette[i % std::size(kPalette)];
    const int x = kWidth - kRight - 10 - Raster::text_width(series[i].label) - 24;
    r.fill_rect(x, y, x + 14, y + 9, color);
    r.text(x + 22, y, series[i].label, kBlack);
  }
}

}  // namespace

bool write_log_log_plot(const std::string& path, const std::vector<PlotSeries>& series,
                        const std::string& x_label, const std::string& y_label,
                        std::string& error) {
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points)
      if (!(x > 0 && y > 0)) {
        error = "log-log plot: non-positive value in series " + s.label;
        return false;
      }
  if (series.empty()) {
    error = "log-log plot: nothing to plot";
    return false;
  }
  Raster raster(kWidth, kHeight, kWhite);
  const Frame frame = frame_of(series);
  draw_axes(raster, frame, x_label, y_label);
  for (std::size_t i = 0; i < series.size(); ++i)
    draw_series(raster, frame, series[i], kPalette[i % std::size(kPalette)]);
  draw_legend(raster, series);
  return raster.write_png(path, error);
}

}  // namespace minisolver
