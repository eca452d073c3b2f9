#include "astro/night_sky.h"

#include <erfa.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "astro/astrometry.h"
#include "astro/star_catalogue.h"
#include "astro/sun.h"
#include "common/night_sky.glsl"
#include "core/spectrum.h"

namespace firmament::astro {
namespace {

glm::dvec3 fromSpherical(double longitude, double latitude) {
  double p[3];
  eraS2c(longitude, latitude, p);
  return {p[0], p[1], p[2]};
}

// An ENU unit vector -> ICRS unit vector through ERFA's observed -> CIRS -> ICRS chain.
glm::dvec3 enuToIcrs(const glm::dvec3& enu, eraASTROM& astrom) {
  const double zenith = std::acos(std::clamp(enu.z, -1.0, 1.0));
  const double azimuth = std::atan2(enu.x, enu.y);  // clockwise from north
  double ri = 0.0, di = 0.0, rc = 0.0, dc = 0.0;
  eraAtoiq("A", azimuth, zenith, &astrom, &ri, &di);
  eraAticq(ri, di, &astrom, &rc, &dc);
  return fromSpherical(rc, dc);
}

// Columns are the images of the ENU axes; Gram-Schmidt removes the ~1e-4 rad that aberration leaves.
glm::dmat3 orthonormalColumns(glm::dvec3 x, glm::dvec3 y) {
  x = glm::normalize(x);
  y = glm::normalize(y - x * glm::dot(x, y));
  return glm::dmat3(x, y, glm::cross(x, y));
}

}  // namespace

NightSkyFrame nightSkyFrame(const AstroTime& time, const GeodeticLocation& location) {
  eraASTROM astrom = observerAstrometry(time, location);
  const glm::dvec3 east = enuToIcrs({1.0, 0.0, 0.0}, astrom);
  const glm::dvec3 north = enuToIcrs({0.0, 1.0, 0.0}, astrom);

  // ICRS -> ecliptic of date (IAU 2006, eraEcm06), then about the pole to the Sun's longitude.
  double ecm[3][3];
  eraEcm06(time.tt.dayStart, time.tt.dayFraction, ecm);
  const glm::dmat3 icrsToEcliptic = glm::transpose(
      glm::dmat3(ecm[0][0], ecm[0][1], ecm[0][2], ecm[1][0], ecm[1][1], ecm[1][2], ecm[2][0], ecm[2][1], ecm[2][2]));
  const glm::dvec3 sunGeocentric = -earthState(time.tt).heliocentric.position;
  const glm::dvec3 sunEcliptic = icrsToEcliptic * sunGeocentric;
  NightSkyFrame frame;
  frame.sunEclipticLongitude = std::atan2(sunEcliptic.y, sunEcliptic.x);
  const double c = std::cos(frame.sunEclipticLongitude), s = std::sin(frame.sunEclipticLongitude);
  // Rz(-lambda_sun) (glm takes columns): rows (c, s, 0), (-s, c, 0), (0, 0, 1).
  const glm::dmat3 toSunLongitude(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
  frame.enuToSunEcliptic =
      orthonormalColumns(toSunLongitude * (icrsToEcliptic * east), toSunLongitude * (icrsToEcliptic * north));

  // ICRS -> galactic (eraIcrs2g works on angles: convert the two axes).
  auto toGalactic = [](const glm::dvec3& v) {
    double ra = 0.0, dec = 0.0, l = 0.0, b = 0.0, p[3] = {v.x, v.y, v.z};
    eraC2s(p, &ra, &dec);
    eraIcrs2g(ra, dec, &l, &b);
    return fromSpherical(l, b);
  };
  frame.enuToGalactic = orthonormalColumns(toGalactic(east), toGalactic(north));
  return frame;
}

NightSkyTerms nightSkySpectralRadiance(const NightSkyFrame& frame, const glm::dvec3& directionEnu, double wavelengthNm,
                                       double binWidthNm, double observerRadius, double planetRadius,
                                       double airglowScale) {
  const glm::dvec3 d = glm::normalize(directionEnu);
  const double solar = solarIrradianceTopOfAtmosphere()(wavelengthNm);
  NightSkyTerms terms;
  terms.airglow =
      shared::airglowSpectralRadiance(wavelengthNm, binWidthNm, d.z, observerRadius, planetRadius, airglowScale);
  terms.zodiacal = shared::zodiacalSolarSpectrumFactor(frame.enuToSunEcliptic * d) * solar;
  terms.stellar = shared::stellarBackgroundSolarSpectrumFactor((frame.enuToGalactic * d).z) * solar;
  return terms;
}

NightSkyTerms nightSkyLuminance(const NightSkyFrame& frame, const glm::dvec3& directionEnu, double observerRadius,
                                double planetRadius, double airglowScale) {
  NightSkyTerms sum;
  for (double wavelength = 360.0; wavelength <= 830.0; wavelength += 1.0) {
    const double ybar = cie1931ColorMatching(wavelength).y;
    const NightSkyTerms l =
        nightSkySpectralRadiance(frame, directionEnu, wavelength, 1.0, observerRadius, planetRadius, airglowScale);
    sum.airglow += l.airglow * ybar;
    sum.zodiacal += l.zodiacal * ybar;
    sum.stellar += l.stellar * ybar;
  }
  sum.airglow *= kMaxLuminousEfficacy;
  sum.zodiacal *= kMaxLuminousEfficacy;
  sum.stellar *= kMaxLuminousEfficacy;
  return sum;
}

double surfaceBrightnessMagnitude(double luminance) {
  return -2.5 * std::log10(luminance / surfaceBrightnessLuminance(0.0));
}

double surfaceBrightnessLuminance(double magnitudePerSquareArcsecond) {
  constexpr double kArcsecond = std::numbers::pi / (180.0 * 3600.0);
  return kZeroMagnitudeIlluminanceLux / (kArcsecond * kArcsecond) * std::pow(10.0, -0.4 * magnitudePerSquareArcsecond);
}

}  // namespace firmament::astro
