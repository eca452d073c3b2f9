#pragma once
// The ERFA observer context shared by the Sun, the Moon and the stars: one eraASTROM per place and
// instant, and the step from CIRS to an observed direction with the chosen refraction. Internal to
// astro/ (it exposes ERFA's types); the public interfaces are topocentric.h and star_catalogue.h.
#include <erfa.h>

#include "astro/geodetic.h"
#include "astro/refraction.h"
#include "astro/time.h"
#include "astro/topocentric.h"

namespace firmament::astro {

// Star-independent astrometry parameters (eraApco) for an observer: barycentric position and velocity
// (annual + diurnal aberration), IAU 2006/2000A bias-precession-nutation, Earth rotation on UT1, the
// WGS84 site; polar motion zero; refraction constants zero (refraction is applied by observeCirs).
eraASTROM observerAstrometry(const AstroTime& time, const GeodeticLocation& location);

// CIRS right ascension and declination (radians) -> observed zenith and azimuth: eraAtioq without
// refraction for the geometric zenith, then the refraction that `conditions` ask for (SPA's formula,
// ERFA's eraRefco model, or none). `distance` is left 0.
TopocentricPosition observeCirs(double rightAscension, double declination, const eraASTROM& astrom,
                                const ObservingConditions& conditions);

}  // namespace firmament::astro
