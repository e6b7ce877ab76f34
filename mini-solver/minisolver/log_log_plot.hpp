// A small log-log line plot written as a PNG with libpng: decade grid and tick labels, one
// colored line with square markers per series, a legend. Text uses a built-in 3x5 pixel font
// (digits, capitals, - . _ and space), so no font library is needed.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace minisolver {

struct PlotSeries {
  std::string label;
  std::vector<std::pair<double, double>> points;  // (x, y), both positive
};

bool write_log_log_plot(const std::string& path, const std::vector<PlotSeries>& series,
                        const std::string& x_label, const std::string& y_label, std::string& error);

}  // namespace minisolver
