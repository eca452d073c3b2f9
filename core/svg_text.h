#pragma once
// Text in SVG documents, shared by the plot writers (core/svg_xy_plot, weather/svg_plot).
#include <string>

namespace firmament {

// XML-escapes <, >, & and " so labels and titles are safe inside elements and attributes.
std::string svgEscape(const std::string& text);

// A number as the shortest of %g's forms, for axis labels.
std::string svgNumber(double value);

}  // namespace firmament
