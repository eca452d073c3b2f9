#include "astro/star_catalogue.h"

#include <erfa.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "astro/astrometry.h"
#include "core/error.h"
#include "core/spectrum.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kHour = std::numbers::pi / 12.0;

[[noreturn]] void malformed(const std::filesystem::path& path, int line, const std::string& what) {
  throw InputError("star catalogue " + path.string() + ", line " + std::to_string(line) + ": " + what +
                   " (xplanet's star format: Dec[deg] RA[hours] V \"name\" HR HD SAO)");
}

// Reads one number from `in`; `field` names it and its allowed range for the message.
double readField(std::istringstream& in, const std::filesystem::path& path, int line, const char* field, double lo,
                 double hi, const char* allowed) {
  double value = 0.0;
  if (!(in >> value) || !std::isfinite(value))
    malformed(path, line, std::string("missing or unreadable ") + field + "; allowed: " + allowed);
  if (value < lo || value > hi) {
    std::ostringstream message;
    message << field << " " << value << " is out of range; allowed: " << allowed;
    malformed(path, line, message.str());
  }
  return value;
}

}  // namespace

std::filesystem::path defaultStarCataloguePath() {
  if (const char* env = std::getenv("FIRMAMENT_STAR_CATALOGUE"); env && *env) return env;
  return "/usr/share/xplanet/stars/BSC";
}

StarCatalogue loadStarCatalogue(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file)
    throw InputError("star catalogue " + path.string() +
                     ": cannot be opened; install the Debian package xplanet (apt-get install xplanet) or set "
                     "FIRMAMENT_STAR_CATALOGUE to a file in xplanet's star format");
  StarCatalogue catalogue;
  catalogue.source = path;
  std::string text;
  int lineNumber = 0;
  while (std::getline(file, text)) {
    ++lineNumber;
    const size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream in(text);
    CatalogueStar star;
    star.declination = readField(in, path, lineNumber, "declination", -90.0, 90.0, "-90 to 90 degrees") * kDegree;
    star.rightAscension = readField(in, path, lineNumber, "right ascension", 0.0, 24.0, "0 to 24 hours") * kHour;
    star.vMagnitude = readField(in, path, lineNumber, "V magnitude", -2.0, 16.0, "-2 to 16");
    star.bMinusV = std::numeric_limits<double>::quiet_NaN();
    // The rest is optional: a quoted name, then the HR number (xplanet itself reads only three columns).
    std::string rest;
    std::getline(in, rest);
    const size_t open = rest.find('"');
    if (open != std::string::npos) {
      const size_t close = rest.find('"', open + 1);
      if (close == std::string::npos) malformed(path, lineNumber, "unterminated quoted name");
      star.name = rest.substr(open + 1, close - open - 1);
      star.name.erase(0, star.name.find_first_not_of(' '));
      std::istringstream numbers(rest.substr(close + 1));
      int hr = 0;
      if (numbers >> hr) star.brightStarNumber = hr;
    }
    catalogue.stars.push_back(std::move(star));
  }
  if (file.bad()) throw InputError("star catalogue " + path.string() + ": read error");
  if (catalogue.stars.empty())
    throw InputError("star catalogue " + path.string() + ": holds no star (expected lines `Dec RA V ...`)");
  return catalogue;
}

StarCatalogue loadDefaultStarCatalogue() { return loadStarCatalogue(defaultStarCataloguePath()); }

double starIlluminanceLux(double vMagnitude) {
  return kZeroMagnitudeIlluminanceLux * std::pow(10.0, -0.4 * vMagnitude);
}

double starTemperatureFromBMinusV(double bMinusV) {
  const double bv = std::clamp(bMinusV, -0.4, 2.0);
  return 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
}

glm::dvec3 blackbodyRec709UnitLuminance(double temperatureKelvin) {
  // Planck's law up to a constant factor (the result is normalised): λ^-5 / (exp(hc / λkT) - 1).
  constexpr double kSecondRadiationConstant = 1.438776877e7;  // hc/k in nm·K (CODATA 2018)
  TabulatedSpectrum planck;
  planck.firstWavelength = 360.0;
  planck.spacing = 1.0;
  for (double wavelength = 360.0; wavelength <= 830.0; wavelength += 1.0) {
    const double x = kSecondRadiationConstant / (wavelength * temperatureKelvin);
    planck.values.push_back(std::pow(wavelength / 550.0, -5.0) / std::expm1(x));
  }
  const glm::dvec3 rgb = spectrumToLinearRec709(planck);
  const double luminance = 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
  return rgb / luminance;
}

std::vector<ApparentStar> apparentStars(const StarCatalogue& catalogue, const AstroTime& time,
                                        const GeodeticLocation& location, const ObservingConditions& conditions) {
  const eraASTROM astrom = observerAstrometry(time, location);
  std::vector<ApparentStar> result;
  result.reserve(catalogue.stars.size());
  eraASTROM context = astrom;  // eraAtciqz takes a non-const pointer but only reads it
  for (size_t i = 0; i < catalogue.stars.size(); ++i) {
    const CatalogueStar& star = catalogue.stars[i];
    // ICRS -> CIRS for a star at infinity with no space motion: light deflection by the Sun, aberration,
    // bias-precession-nutation (the "quick" eraAtciqz, which reads the context eraApco filled).
    double rightAscension = 0.0, declination = 0.0;
    eraAtciqz(star.rightAscension, star.declination, &context, &rightAscension, &declination);
    const TopocentricPosition observed = observeCirs(rightAscension, declination, context, conditions);
    ApparentStar apparent;
    apparent.zenith = observed.zenith;
    apparent.azimuth = observed.azimuth;
    apparent.geometricZenith = observed.geometricZenith;
    apparent.directionEnu = observed.directionEnu();
    apparent.illuminanceLux = starIlluminanceLux(star.vMagnitude);
    apparent.rgb =
        std::isfinite(star.bMinusV)
            ? blackbodyRec709UnitLuminance(starTemperatureFromBMinusV(star.bMinusV)) * apparent.illuminanceLux
            : glm::dvec3(apparent.illuminanceLux);
    apparent.catalogueIndex = int(i);
    result.push_back(apparent);
  }
  return result;
}

}  // namespace firmament::astro
