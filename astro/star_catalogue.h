#pragma once
// The stars: a catalogue read at run time from an installed package (xplanet's copy of the Yale Bright
// Star Catalogue, 5th revised edition), their apparent places for a place and instant (ERFA), and
// their light: V magnitude -> illuminance, B-V -> colour (docs/night.md, "Stars").
#include <glm/vec3.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "astro/geodetic.h"
#include "astro/refraction.h"
#include "astro/time.h"

namespace firmament::astro {

// One catalogue entry: ICRS/J2000 place (the BSC's J2000 columns), V magnitude, and B-V where the
// catalogue has it (NaN where it does not: xplanet's BSC keeps only position and V).
struct CatalogueStar {
  double rightAscension = 0.0;  // radians, ICRS, epoch J2000
  double declination = 0.0;     // radians
  double vMagnitude = 0.0;      // Johnson V
  double bMinusV = 0.0;         // Johnson B-V, NaN when unknown
  int brightStarNumber = 0;     // HR (BSC) number, 0 when the catalogue has none
  std::string name;             // as the catalogue spells it ("9Alp CMa"), may be empty
};

struct StarCatalogue {
  std::filesystem::path source;
  std::vector<CatalogueStar> stars;
};

// Where the catalogue is read from: $FIRMAMENT_STAR_CATALOGUE when set, else
// /usr/share/xplanet/stars/BSC (Debian package `xplanet`).
std::filesystem::path defaultStarCataloguePath();

// Reads a catalogue in xplanet's star format: one star a line, `Dec(deg) RA(hours) V "name" HR HD SAO`,
// '#' comments and blank lines skipped. Throws InputError naming the file, the line and the field with
// its allowed range when the file is missing, unreadable or malformed, or holds no star.
StarCatalogue loadStarCatalogue(const std::filesystem::path& path);
// loadStarCatalogue(defaultStarCataloguePath()); the error for a missing file says which package and
// which environment variable provide it.
StarCatalogue loadDefaultStarCatalogue();

// Illuminance of a star of visual magnitude V outside the atmosphere, normal to the light:
// E = 2.54e-6 lx · 10^(-0.4 V)  (Allen, Astrophysical Quantities, 3rd ed. 1973: a star of V = 0 gives
// 2.54e-6 lm m^-2; equivalently V = -13.99 - 2.5 log10(E / 1 lx)).
inline constexpr double kZeroMagnitudeIlluminanceLux = 2.54e-6;
double starIlluminanceLux(double vMagnitude);

// Effective temperature from B-V, Ballesteros (2012), "New insights into black bodies", EPL 97, 34008:
//   T = 4600 K · (1 / (0.92 (B-V) + 1.7) + 1 / (0.92 (B-V) + 0.62)),
// B-V clamped to [-0.4, 2.0], the range of the stars the fit was made on.
double starTemperatureFromBMinusV(double bMinusV);

// Linear Rec.709 colour of a blackbody of temperature T (kelvin) through the CIE 1931 observer
// (core/spectrum.h), scaled so that its luminance Y is 1: multiply by a star's illuminance in lux.
glm::dvec3 blackbodyRec709UnitLuminance(double temperatureKelvin);

// A star as seen from a place at an instant.
struct ApparentStar {
  glm::dvec3 directionEnu{0.0, 0.0, 1.0};  // unit vector, x east, y north, z up (refraction applied)
  double zenith = 0.0;                     // apparent zenith angle, radians
  double azimuth = 0.0;                    // clockwise from north, radians
  double geometricZenith = 0.0;            // before refraction
  double illuminanceLux = 0.0;             // outside the atmosphere, normal to the light
  glm::dvec3 rgb{0.0};                     // linear Rec.709 whose luminance is illuminanceLux
  int catalogueIndex = 0;                  // into StarCatalogue::stars
};

// Apparent places of every catalogue star (also those below the horizon: the caller culls) at `time` from
// `location`: ERFA's ICRS -> observed chain with one eraApco context per call (eraAtciqz: light deflection
// by the Sun, annual and diurnal aberration, precession-nutation IAU 2006/2000A; eraAtioq: Earth rotation
// and the horizon), then refraction as `conditions` ask. No proper motion or parallax: xplanet's BSC has
// none (the largest effect among its stars is 61 Cyg's 5.2"/yr; Arcturus 2.3"/yr; docs/night.md). A star
// whose B-V is unknown gets the Rec.709 white (D65) at its luminance.
std::vector<ApparentStar> apparentStars(const StarCatalogue& catalogue, const AstroTime& time,
                                        const GeodeticLocation& location, const ObservingConditions& conditions = {});

}  // namespace firmament::astro
