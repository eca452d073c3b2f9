#pragma once
// The Moon: position (eraMoon98, Meeus's truncated ELP-2000/82 series) and phase.
#include "astro/geodetic.h"
#include "astro/refraction.h"
#include "astro/time.h"
#include "astro/topocentric.h"

namespace firmament::astro {

// Geocentric position of the Moon's centre, geometric (no light time, no aberration, no nutation),
// on the mean ecliptic and equinox of date (IAU 2006, eraEcm06): the frame of Meeus's chapter 47.
struct EclipticPosition {
  double longitude = 0.0;  // radians in [0, 2 pi)
  double latitude = 0.0;   // radians
  double distance = 0.0;   // metres, centre to centre
};
EclipticPosition moonGeocentricEcliptic(const AstroTime& time);

// The Moon's barycentric state at TT (Earth's from eraEpv00 plus the Moon's geocentric from eraMoon98).
// eraMoon98: 2.9" RMS, 18" worst, against ELP/MPP02 over 1950-2100.
BarycentricState moonBarycentricState(const JulianDate& tt);

// Topocentric zenith and azimuth of the Moon's centre; parallax (up to ~1 degree) included.
TopocentricPosition moonPosition(const AstroTime& time, const GeodeticLocation& location,
                                 const ObservingConditions& conditions = {});

// How much of the Moon's disc is lit, seen from the Earth's centre (Meeus 1998, ch. 48).
struct MoonPhase {
  double illuminatedFraction = 0.0;  // k = (1 + cos i) / 2, 0 new .. 1 full
  double phaseAngle = 0.0;           // i: the Sun-Moon-Earth angle, radians (0 full, pi new)
  double elongation = 0.0;           // geocentric Sun-Moon angle, radians
  bool waxing = false;               // the Moon is east of the Sun (ecliptic longitude ahead by < 180°)
};
MoonPhase moonPhase(const AstroTime& time);

}  // namespace firmament::astro
