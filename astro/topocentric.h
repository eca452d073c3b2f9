#pragma once
// Where a solar-system body appears from a place on the Earth: the ERFA (IAU SOFA) astrometry
// pipeline for a body at a finite distance, from barycentric position to observed zenith and azimuth.
#include <glm/vec3.hpp>

#include "astro/geodetic.h"
#include "astro/refraction.h"
#include "astro/time.h"

namespace firmament::astro {

// A body's state relative to the solar-system barycentre, on BCRS (ICRS-aligned) axes:
// position in astronomical units, velocity in au per day (ERFA's units).
struct BarycentricState {
  glm::dvec3 position{0.0};
  glm::dvec3 velocity{0.0};
};

// The Earth's centre at a TT instant (eraEpv00, accurate to a few km against DE405).
struct EarthState {
  BarycentricState barycentric;
  BarycentricState heliocentric;  // relative to the Sun's centre
};
EarthState earthState(const JulianDate& tt);

// Topocentric horizontal coordinates of a body.
struct TopocentricPosition {
  double zenith = 0.0;           // apparent zenith angle (refraction applied), radians
  double azimuth = 0.0;          // clockwise from north (east = pi/2), radians in [0, 2 pi)
  double geometricZenith = 0.0;  // zenith angle before refraction, radians
  double distance = 0.0;         // observer to body, metres

  double elevation() const;  // pi/2 - zenith
  // Unit vector towards the body in the local frame: x east, y north, z up.
  glm::dvec3 directionEnu() const { return enuDirection(zenith, azimuth); }
};

// Observes a body: light time, annual and diurnal aberration (eraAb with the observer's barycentric
// velocity from eraApco), frame bias and precession-nutation IAU 2006/2000A (eraPnm06a), Earth rotation
// (eraEra00 on UT1), topocentric parallax (the observer on WGS84), then refraction as `conditions` ask.
// Left out: light deflection by the Sun (undefined for the Sun itself, a few milliarcseconds for the
// Moon) and polar motion (under 0.5 arcsecond, and needs IERS data).
TopocentricPosition observe(const BarycentricState& body, const AstroTime& time, const GeodeticLocation& location,
                            const ObservingConditions& conditions);

}  // namespace firmament::astro
