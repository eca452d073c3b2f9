#include "astro/moon.h"

#include <erfa.h>
#include <erfam.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace firmament::astro {
namespace {

// The Moon's geocentric state on GCRS axes, au and au/day.
BarycentricState moonGeocentricState(const JulianDate& tt) {
  double pv[2][3];
  eraMoon98(tt.dayStart, tt.dayFraction, pv);
  return {{pv[0][0], pv[0][1], pv[0][2]}, {pv[1][0], pv[1][1], pv[1][2]}};
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  // atan2 of |a x b| and a . b keeps precision at small and near-pi angles, where acos does not.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

EclipticPosition moonGeocentricEcliptic(const AstroTime& time) {
  glm::dvec3 gcrs = moonGeocentricState(time.tt).position;
  double toEcliptic[3][3], p[3] = {gcrs.x, gcrs.y, gcrs.z}, ecliptic[3];
  eraEcm06(time.tt.dayStart, time.tt.dayFraction, toEcliptic);
  eraRxp(toEcliptic, p, ecliptic);
  EclipticPosition result;
  eraC2s(ecliptic, &result.longitude, &result.latitude);
  result.longitude = eraAnp(result.longitude);
  result.distance = glm::length(gcrs) * ERFA_DAU;
  return result;
}

BarycentricState moonBarycentricState(const JulianDate& tt) {
  EarthState earth = earthState(tt);
  BarycentricState moon = moonGeocentricState(tt);
  return {earth.barycentric.position + moon.position, earth.barycentric.velocity + moon.velocity};
}

TopocentricPosition moonPosition(const AstroTime& time, const GeodeticLocation& location,
                                 const ObservingConditions& conditions) {
  return observe(moonBarycentricState(time.tt), time, location, conditions);
}

MoonPhase moonPhase(const AstroTime& time) {
  EarthState earth = earthState(time.tt);
  glm::dvec3 sun = -earth.heliocentric.position;  // geocentric Sun, au
  glm::dvec3 moon = moonGeocentricState(time.tt).position;
  MoonPhase phase;
  phase.elongation = angleBetween(sun, moon);
  // The phase angle is the angle at the Moon between the Sun and the Earth (Meeus eq. 48.3 in vector form).
  phase.phaseAngle = angleBetween(sun - moon, -moon);
  phase.illuminatedFraction = std::clamp((1.0 + std::cos(phase.phaseAngle)) / 2.0, 0.0, 1.0);
  // Waxing while the Moon leads the Sun eastwards: the north pole of the ecliptic sees sun x moon up.
  double toEcliptic[3][3];
  eraEcm06(time.tt.dayStart, time.tt.dayFraction, toEcliptic);
  glm::dvec3 eclipticPole(toEcliptic[2][0], toEcliptic[2][1], toEcliptic[2][2]);
  phase.waxing = glm::dot(glm::cross(sun, moon), eclipticPole) > 0.0;
  return phase;
}

}  // namespace firmament::astro
