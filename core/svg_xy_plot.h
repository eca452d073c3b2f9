#pragma once
// A small SVG scatter/line plot of (x, y) series with linear or logarithmic axes: error against run
// time in the benchmark reports. Self-contained text output; no dependencies. (weather/svg_plot.h is
// the time-series plot with two y axes; this one has one y axis, per-series x values, log axes,
// point labels and reference lines.)
#include <cstddef>
#include <string>
#include <vector>

namespace firmament {

struct XyPlotSeries {
  std::string name;
  std::string colour;               // any SVG colour, e.g. "#1f77b4"
  std::vector<double> x, y;         // one point per index; points not drawable on the axes are skipped
  std::vector<std::string> labels;  // optional, one per point, drawn beside it
  bool connect = true;              // join the points in order with a line
};

// A horizontal reference line (e.g. an error budget), drawn dashed across the plot.
struct XyPlotLine {
  std::string name;
  double y = 0.0;
  std::string colour = "#888888";
};

struct XyPlot {
  std::string title, xLabel, yLabel;
  bool logX = false, logY = false;  // a log axis drops values <= 0
  std::vector<XyPlotSeries> series;
  std::vector<XyPlotLine> lines;
  int width = 900, height = 560;
};

// A palette of ten distinguishable series colours (Tableau 10), repeated past the tenth.
const char* plotColour(size_t index);

// The SVG document. Axes span the data (and the reference lines), padded; non-finite values are
// skipped.
std::string renderXySvg(const XyPlot& plot);

}  // namespace firmament
