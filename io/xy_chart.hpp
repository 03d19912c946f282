#pragma once
// A plain x-y chart as a PNG (cairo): grid, ticks, axis labels, a title, line and/or marker
// series with a legend, and horizontal reference lines. For reports (calibration convergence,
// response-surface slices); data in the caller's units, as labelled.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace cdem {

struct ChartSeries {
  std::string label;
  std::vector<double> x, y;  // same length; non-finite points are skipped
  std::array<double, 3> rgb{0.1, 0.3, 0.8};
  bool line = true;
  bool markers = true;
};

struct ChartLine {  // a horizontal reference line, dashed
  double y = 0;
  std::string label;
};

struct XyChart {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  std::vector<ChartLine> lines;
  bool y_from_zero = false;  // the y axis starts at 0 (a quantity that cannot be negative)
  bool x_integer = false;    // x ticks only at whole numbers (iterations, run counts)
};

// Colour number i of a fixed palette (cycles), for series that need distinct colours.
std::array<double, 3> chart_colour(std::size_t i);

// Writes the chart atomically; the axes span every finite point and reference line, padded.
void draw_xy_chart_png(const XyChart& chart, const std::filesystem::path& png, int width_px = 900,
                       int height_px = 600);

}  // namespace cdem
