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

struct ChartMark {  // a point marked by a ring, with its label beside it
  double x = 0, y = 0;
  std::string label;
  std::array<double, 3> rgb{0, 0, 0};
};

struct ChartBand {  // a vertical band x0 <= x <= x1, shaded, labelled at its top
  double x0 = 0, x1 = 0;
  std::string label;
};

struct XyChart {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  std::vector<ChartLine> lines;
  std::vector<ChartMark> marks;
  std::vector<ChartBand> bands;
  std::vector<std::string> notes;  // lines of text in a box at the top left of the plot
  bool y_from_zero = false;        // the y axis starts at 0 (a quantity that cannot be negative)
  bool x_integer = false;          // x ticks only at whole numbers (iterations, run counts)
};

// Colour number i of a fixed palette (cycles), for series that need distinct colours.
std::array<double, 3> chart_colour(std::size_t i);

// Writes the chart atomically; the axes span every finite point, reference line, mark and
// band, padded.
void draw_xy_chart_png(const XyChart& chart, const std::filesystem::path& png, int width_px = 900,
                       int height_px = 600);

// Several charts side by side in one PNG, each width_px / charts.size() wide.
void draw_xy_charts_png(const std::vector<XyChart>& charts, const std::filesystem::path& png,
                        int width_px, int height_px);

}  // namespace cdem
