#pragma once
// A small SVG line-plot writer for time series (stats.csv plots): one x axis, a left and a right y
// axis, a legend. Self-contained text output; no dependencies.
#include <string>
#include <vector>

namespace firmament::weather {

struct PlotSeries {
  std::string name;
  std::string colour;          // any SVG colour, e.g. "#1f77b4"
  std::vector<double> values;  // one per x
  bool rightAxis = false;
};

struct LinePlot {
  std::string title, xLabel, leftLabel, rightLabel;
  std::vector<double> x;
  std::vector<PlotSeries> series;
  int width = 900, height = 480;
};

// The SVG document. Non-finite values break the line; axes span the data (left axis from 0).
std::string renderSvg(const LinePlot& plot);

}  // namespace firmament::weather
