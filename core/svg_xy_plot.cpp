#include "core/svg_xy_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/svg_text.h"

namespace firmament {
namespace {

// One axis: the data range mapped to pixels, linear or in log10, with tick positions.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // in axis units (log10 of the value on a log axis)

  bool accepts(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double unit(double v) const { return log ? std::log10(v) : v; }

  void fit(double minValue, double maxValue) {
    if (!(minValue <= maxValue)) minValue = maxValue = log ? 1.0 : 0.0;
    lo = unit(minValue);
    hi = unit(maxValue);
    if (log) {
      lo = std::floor(lo + 1e-9);
      hi = std::ceil(hi - 1e-9);
      if (hi <= lo) hi = lo + 1.0;
    } else {
      double pad = hi > lo ? 0.05 * (hi - lo) : std::max(1.0, std::abs(hi) * 0.1);
      lo -= pad;
      hi += pad;
    }
  }
  double fraction(double v) const { return (unit(v) - lo) / (hi - lo); }

  // Tick values: decades (plus 2 and 5 when the axis spans at most two decades) on a log axis,
  // 1/2/5 × 10^k steps on a linear one.
  std::vector<double> ticks() const {
    std::vector<double> out;
    if (log) {
      const bool fine = hi - lo <= 2.0;
      for (int e = int(std::floor(lo)); e <= int(std::ceil(hi)); ++e)
        for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
          double v = m * std::pow(10.0, e);
          double u = std::log10(v);
          if (u >= lo - 1e-9 && u <= hi + 1e-9) out.push_back(v);
        }
      return out;
    }
    double span = hi - lo, raw = span / 6.0, power = std::pow(10.0, std::floor(std::log10(raw)));
    double m = raw / power;
    double step = (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * power;
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step)
      out.push_back(std::abs(v) < 1e-12 * span ? 0.0 : v);
    return out;
  }
};

}  // namespace

const char* plotColour(size_t index) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return kColours[index % 10];
}

std::string renderXySvg(const XyPlot& p) {
  const double left = 80, right = 200, top = 40, bottom = 55;
  const double w = p.width - left - right, h = p.height - top - bottom;

  Axis ax{p.logX}, ay{p.logY};
  double xMin = std::numeric_limits<double>::infinity(), xMax = -xMin, yMin = xMin, yMax = -xMin;
  for (const auto& s : p.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (ax.accepts(s.x[i]) && ay.accepts(s.y[i])) {
        xMin = std::min(xMin, s.x[i]), xMax = std::max(xMax, s.x[i]);
        yMin = std::min(yMin, s.y[i]), yMax = std::max(yMax, s.y[i]);
      }
  for (const auto& l : p.lines)
    if (ay.accepts(l.y)) yMin = std::min(yMin, l.y), yMax = std::max(yMax, l.y);
  ax.fit(xMin, xMax);
  ay.fit(yMin, yMax);
  auto px = [&](double v) { return left + w * ax.fraction(v); };
  auto py = [&](double v) { return top + h * (1.0 - ay.fraction(v)); };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << p.width << "\" height=\"" << p.height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left + w / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << svgEscape(p.title)
      << "</text>\n";
  for (double t : ax.ticks()) {
    double x = px(t);
    svg << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << top + h
        << "\" stroke=\"#eeeeee\"/>\n<text x=\"" << x << "\" y=\"" << top + h + 16 << "\" text-anchor=\"middle\">"
        << svgNumber(t) << "</text>\n";
  }
  for (double t : ay.ticks()) {
    double y = py(t);
    svg << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + w << "\" y2=\"" << y
        << "\" stroke=\"#eeeeee\"/>\n<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">"
        << svgNumber(t) << "</text>\n";
  }
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << w << "\" height=\"" << h
      << "\" fill=\"none\" stroke=\"black\"/>\n"
      << "<text x=\"" << left + w / 2 << "\" y=\"" << p.height - 12 << "\" text-anchor=\"middle\">"
      << svgEscape(p.xLabel) << (p.logX ? " (log)" : "") << "</text>\n"
      << "<text transform=\"translate(18," << top + h / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
      << svgEscape(p.yLabel) << (p.logY ? " (log)" : "") << "</text>\n";

  double legendY = top + 10;
  auto legend = [&](const std::string& name, const std::string& colour, bool dashed) {
    svg << "<line x1=\"" << left + w + 12 << "\" y1=\"" << legendY << "\" x2=\"" << left + w + 36 << "\" y2=\""
        << legendY << "\" stroke=\"" << colour << "\" stroke-width=\"2\"" << (dashed ? " stroke-dasharray=\"6 4\"" : "")
        << "/>\n<text x=\"" << left + w + 42 << "\" y=\"" << legendY + 4 << "\">" << svgEscape(name) << "</text>\n";
    legendY += 18;
  };
  for (const auto& l : p.lines) {
    if (!ay.accepts(l.y)) continue;
    double y = py(l.y);
    svg << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + w << "\" y2=\"" << y << "\" stroke=\""
        << l.colour << "\" stroke-dasharray=\"6 4\"/>\n";
    legend(l.name, l.colour, true);
  }
  for (const auto& s : p.series) {
    std::ostringstream path;
    bool pen = false;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!(ax.accepts(s.x[i]) && ay.accepts(s.y[i]))) {
        pen = false;
        continue;
      }
      double x = px(s.x[i]), y = py(s.y[i]);
      path << (pen ? " L" : " M") << x << ' ' << y;
      pen = true;
      svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"3.5\" fill=\"" << s.colour << "\"/>\n";
      if (i < s.labels.size() && !s.labels[i].empty())
        svg << "<text x=\"" << x + 5 << "\" y=\"" << y - 5 << "\" font-size=\"10\" fill=\"" << s.colour << "\">"
            << svgEscape(s.labels[i]) << "</text>\n";
    }
    if (s.connect && !path.str().empty())
      svg << "<path d=\"" << path.str() << "\" fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"1.5\"/>\n";
    legend(s.name, s.colour, false);
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace firmament
