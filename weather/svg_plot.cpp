#include "weather/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/svg_text.h"

namespace firmament::weather {
namespace {

// A "nice" tick step (1, 2 or 5 × 10^k) for about `count` ticks over `span`.
double niceStep(double span, int count) {
  if (!(span > 0.0)) return 1.0;
  double raw = span / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  double m = raw / power;
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * power;
}

}  // namespace

std::string renderSvg(const LinePlot& p) {
  const double left = 70, right = 70, top = 40, bottom = 50;
  const double w = p.width - left - right, h = p.height - top - bottom;
  double xMin = p.x.empty() ? 0.0 : p.x.front(), xMax = p.x.empty() ? 1.0 : p.x.back();
  if (!(xMax > xMin)) xMax = xMin + 1.0;
  double yMax[2] = {0.0, 0.0};
  for (const auto& s : p.series)
    for (double v : s.values)
      if (std::isfinite(v)) yMax[s.rightAxis] = std::max(yMax[s.rightAxis], v);
  for (double& m : yMax) {
    double step = niceStep(m > 0 ? m : 1.0, 5);
    m = std::ceil((m > 0 ? m : 1.0) / step) * step;
  }
  auto px = [&](double x) { return left + (x - xMin) / (xMax - xMin) * w; };
  auto py = [&](double y, bool r) { return top + h - y / yMax[r] * h; };

  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << p.width << "\" height=\"" << p.height
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"" << p.width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << svgEscape(p.title)
    << "</text>\n";
  // Grid and ticks.
  double xs = niceStep(xMax - xMin, 8);
  for (double x = std::ceil(xMin / xs) * xs; x <= xMax + 1e-9; x += xs)
    o << "<line x1=\"" << px(x) << "\" y1=\"" << top << "\" x2=\"" << px(x) << "\" y2=\"" << top + h
      << "\" stroke=\"#ddd\"/><text x=\"" << px(x) << "\" y=\"" << top + h + 16 << "\" text-anchor=\"middle\">"
      << svgNumber(x) << "</text>\n";
  for (int r = 0; r < 2; ++r) {
    double ys = niceStep(yMax[r], 5);
    for (double y = 0; y <= yMax[r] + 1e-9; y += ys) {
      if (r == 0)
        o << "<line x1=\"" << left << "\" y1=\"" << py(y, 0) << "\" x2=\"" << left + w << "\" y2=\"" << py(y, 0)
          << "\" stroke=\"#ddd\"/>";
      o << "<text x=\"" << (r ? left + w + 6 : left - 6) << "\" y=\"" << py(y, r) + 4 << "\" text-anchor=\""
        << (r ? "start" : "end") << "\">" << svgNumber(y) << "</text>\n";
    }
  }
  o << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << w << "\" height=\"" << h
    << "\" fill=\"none\" stroke=\"black\"/>\n";
  o << "<text x=\"" << left + w / 2 << "\" y=\"" << p.height - 10 << "\" text-anchor=\"middle\">" << svgEscape(p.xLabel)
    << "</text>\n";
  o << "<text transform=\"translate(16," << top + h / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
    << svgEscape(p.leftLabel) << "</text>\n";
  o << "<text transform=\"translate(" << p.width - 14 << "," << top + h / 2 << ") rotate(90)\" text-anchor=\"middle\">"
    << svgEscape(p.rightLabel) << "</text>\n";
  // Lines.
  int legend = 0;
  for (const auto& s : p.series) {
    std::string path;
    bool pen = false;
    for (size_t i = 0; i < s.values.size() && i < p.x.size(); ++i) {
      if (!std::isfinite(s.values[i])) {
        pen = false;
        continue;
      }
      char seg[64];
      std::snprintf(seg, sizeof seg, "%s%.1f,%.1f ", pen ? "L" : "M", px(p.x[i]), py(s.values[i], s.rightAxis));
      path += seg;
      pen = true;
    }
    o << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"1.8\""
      << (s.rightAxis ? " stroke-dasharray=\"6,3\"" : "") << "/>\n";
    double ly = top + 14 + 16 * legend++;
    o << "<line x1=\"" << left + 10 << "\" y1=\"" << ly << "\" x2=\"" << left + 34 << "\" y2=\"" << ly << "\" stroke=\""
      << s.colour << "\" stroke-width=\"2\"" << (s.rightAxis ? " stroke-dasharray=\"6,3\"" : "") << "/><text x=\""
      << left + 40 << "\" y=\"" << ly + 4 << "\">" << svgEscape(s.name) << (s.rightAxis ? " (right axis)" : "")
      << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace firmament::weather
