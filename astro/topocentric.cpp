#include "astro/topocentric.h"

#include "astro/astrometry.h"

#include <erfa.h>
#include <erfam.h>
#include <glm/geometric.hpp>

#include <numbers>

namespace firmament::astro {
namespace {

glm::dvec3 toVec(const double p[3]) { return {p[0], p[1], p[2]}; }

// Light travel time, in days, over a distance in au (ERFA_AULT: light time for 1 au, seconds).
double lightTimeDays(double distanceAu) { return distanceAu * ERFA_AULT / ERFA_DAYSEC; }

}  // namespace

double TopocentricPosition::elevation() const { return std::numbers::pi / 2 - zenith; }

EarthState earthState(const JulianDate& tt) {
  double heliocentric[2][3], barycentric[2][3];
  // The status only warns for dates outside 1900-2100, where accuracy degrades gracefully.
  eraEpv00(tt.dayStart, tt.dayFraction, heliocentric, barycentric);
  return {{toVec(barycentric[0]), toVec(barycentric[1])}, {toVec(heliocentric[0]), toVec(heliocentric[1])}};
}

eraASTROM observerAstrometry(const AstroTime& time, const GeodeticLocation& location) {
  const JulianDate& tt = time.tt;
  EarthState earth = earthState(tt);
  double earthBarycentric[2][3] = {
      {earth.barycentric.position.x, earth.barycentric.position.y, earth.barycentric.position.z},
      {earth.barycentric.velocity.x, earth.barycentric.velocity.y, earth.barycentric.velocity.z}};
  double earthHeliocentric[3] = {earth.heliocentric.position.x, earth.heliocentric.position.y,
                                 earth.heliocentric.position.z};

  // Celestial intermediate pole (X, Y) and CIO locator s from the IAU 2006/2000A precession-nutation.
  double npb[3][3];
  eraPnm06a(tt.dayStart, tt.dayFraction, npb);
  double x = 0.0, y = 0.0;
  eraBpn2xy(npb, &x, &y);
  double s = eraS06(tt.dayStart, tt.dayFraction, x, y);
  double earthRotationAngle = eraEra00(time.ut1.dayStart, time.ut1.dayFraction);
  double tioLocator = eraSp00(tt.dayStart, tt.dayFraction);

  // Star-independent parameters for this observer: barycentric position and velocity (with the
  // diurnal motion), the bias-precession-nutation matrix and the local Earth rotation. Refraction is
  // switched off here and applied by observeCirs, so the geometric zenith comes out too.
  eraASTROM astrom;
  eraApco(tt.dayStart, tt.dayFraction, earthBarycentric, earthHeliocentric, x, y, s, earthRotationAngle,
          location.longitude, location.latitude, location.height, 0.0, 0.0, tioLocator, 0.0, 0.0, &astrom);
  return astrom;
}

TopocentricPosition observeCirs(double rightAscension, double declination, const eraASTROM& astromIn,
                                const ObservingConditions& conditions) {
  eraASTROM astrom = astromIn;
  astrom.refa = astrom.refb = 0.0;
  // CIRS -> observed: Earth rotation, polar motion (zero here), the horizon of the place.
  double azimuth = 0.0, zenith = 0.0, hourAngle = 0.0, observedDec = 0.0, observedRa = 0.0;
  eraAtioq(rightAscension, declination, &astrom, &azimuth, &zenith, &hourAngle, &observedDec, &observedRa);

  TopocentricPosition result;
  result.azimuth = eraAnp(azimuth);
  result.geometricZenith = zenith;
  switch (conditions.refraction) {
    case RefractionModel::None:
      result.zenith = zenith;
      break;
    case RefractionModel::Spa:
      result.zenith =
          zenith - spaRefraction(std::numbers::pi / 2 - zenith, conditions.pressureHpa, conditions.temperatureCelsius);
      break;
    case RefractionModel::Erfa: {
      eraRefco(conditions.pressureHpa, conditions.temperatureCelsius, conditions.relativeHumidity,
               conditions.wavelengthMicrometres, &astrom.refa, &astrom.refb);
      eraAtioq(rightAscension, declination, &astrom, &azimuth, &zenith, &hourAngle, &observedDec, &observedRa);
      result.zenith = zenith;
      break;
    }
  }
  return result;
}

TopocentricPosition observe(const BarycentricState& body, const AstroTime& time, const GeodeticLocation& location,
                            const ObservingConditions& conditions) {
  eraASTROM astrom = observerAstrometry(time, location);

  // Observer -> body, with the body where it was when the light left it (two fixed-point steps converge
  // to far below a millimetre for the Sun and the Moon).
  glm::dvec3 observer = toVec(astrom.eb);
  glm::dvec3 toBody = body.position - observer;
  for (int i = 0; i < 2; ++i) toBody = body.position - body.velocity * lightTimeDays(glm::length(toBody)) - observer;
  double distanceAu = glm::length(toBody);
  glm::dvec3 natural = toBody / distanceAu;

  // Aberration (special-relativistic, the observer's full barycentric velocity), then GCRS -> CIRS.
  double pnat[3] = {natural.x, natural.y, natural.z}, proper[3], cirs[3];
  eraAb(pnat, astrom.v, astrom.em, astrom.bm1, proper);
  eraRxp(astrom.bpn, proper, cirs);
  double rightAscension = 0.0, declination = 0.0;
  eraC2s(cirs, &rightAscension, &declination);

  TopocentricPosition result = observeCirs(rightAscension, declination, astrom, conditions);
  result.distance = distanceAu * ERFA_DAU;
  return result;
}

}  // namespace firmament::astro
