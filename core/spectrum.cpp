#include "core/spectrum.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

namespace firmament {
namespace {

// The range of the colour-matching functions, and the step at which spectra are integrated against
// them: 1 nm resolves the CMFs' 5 nm table under linear interpolation exactly.
constexpr double kVisibleFirst = 360.0;
constexpr double kVisibleLast = 830.0;
constexpr double kIntegrationStep = 1.0;

glm::dvec3 integrateAgainstCmfs(const std::function<double(double)>& spectrum) {
  glm::dvec3 sum(0.0);
  int count = int(std::lround((kVisibleLast - kVisibleFirst) / kIntegrationStep));
  for (int i = 0; i <= count; ++i) {
    double wavelength = kVisibleFirst + i * kIntegrationStep;
    sum += spectrum(wavelength) * cie1931ColorMatching(wavelength);
  }
  return kMaxLuminousEfficacy * kIntegrationStep * sum;
}

// XYZ of a colour with chromaticity (x, y) and luminance Y = 1.
glm::dvec3 xyzFromChromaticity(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

glm::dmat3 deriveXyzToRec709() {
  // ITU-R BT.709-6, table 1, items 1.3 and 1.4: primaries and the D65 white point.
  glm::dmat3 primaries(xyzFromChromaticity(0.64, 0.33), xyzFromChromaticity(0.30, 0.60),
                       xyzFromChromaticity(0.15, 0.06));  // columns: XYZ of R, G, B (column-major)
  glm::dvec3 white = xyzFromChromaticity(0.3127, 0.3290);
  // Scale each primary so that R = G = B = 1 gives the white point.
  glm::dvec3 scale = glm::inverse(primaries) * white;
  glm::dmat3 rgbToXyz(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
  return glm::inverse(rgbToXyz);
}

}  // namespace

double TabulatedSpectrum::operator()(double wavelength) const {
  if (values.empty() || !(wavelength >= firstWavelength) || wavelength > lastWavelength()) return 0.0;
  double position = (wavelength - firstWavelength) / spacing;
  size_t i = std::min(size_t(position), values.size() - 1);
  if (i + 1 == values.size()) return values[i];
  double t = position - double(i);
  return values[i] * (1.0 - t) + values[i + 1] * t;
}

double TabulatedSpectrum::integral() const {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum * spacing;
}

double interpolateSpectrum(std::span<const double> wavelengths, std::span<const double> values, double wavelength) {
  size_t n = std::min(wavelengths.size(), values.size());
  if (n == 0 || !(wavelength >= wavelengths[0]) || wavelength > wavelengths[n - 1]) return 0.0;
  if (n == 1) return values[0];
  // First sample strictly after the wavelength; the segment is [i - 1, i].
  size_t i = size_t(std::upper_bound(wavelengths.begin(), wavelengths.begin() + n, wavelength) - wavelengths.begin());
  if (i >= n) return values[n - 1];
  double t = (wavelength - wavelengths[i - 1]) / (wavelengths[i] - wavelengths[i - 1]);
  return values[i - 1] * (1.0 - t) + values[i] * t;
}

glm::dvec3 cie1931ColorMatching(double wavelength) {
  return {cie1931X()(wavelength), cie1931Y()(wavelength), cie1931Z()(wavelength)};
}

const glm::dmat3& xyzToLinearRec709Matrix() {
  static const glm::dmat3 matrix = deriveXyzToRec709();
  return matrix;
}

glm::dvec3 xyzToLinearRec709(const glm::dvec3& xyz) { return xyzToLinearRec709Matrix() * xyz; }

glm::dvec3 spectrumToXyz(const TabulatedSpectrum& spectrum) {
  return integrateAgainstCmfs([&](double wavelength) { return spectrum(wavelength); });
}

glm::dvec3 spectrumToXyz(std::span<const double> wavelengths, std::span<const double> values) {
  return integrateAgainstCmfs([&](double wavelength) { return interpolateSpectrum(wavelengths, values, wavelength); });
}

glm::dvec3 spectrumToLinearRec709(const TabulatedSpectrum& spectrum) {
  return xyzToLinearRec709(spectrumToXyz(spectrum));
}

glm::dvec3 spectrumToLinearRec709(std::span<const double> wavelengths, std::span<const double> values) {
  return xyzToLinearRec709(spectrumToXyz(wavelengths, values));
}

}  // namespace firmament
