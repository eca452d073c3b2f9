#pragma once
// The Sun as seen from a place on the Earth.
#include <functional>

#include <glm/vec3.hpp>

#include "astro/geodetic.h"
#include "astro/refraction.h"
#include "astro/time.h"
#include "astro/topocentric.h"

namespace firmament::astro {

// The Sun's barycentric state at TT: Earth's barycentric minus heliocentric state (eraEpv00).
BarycentricState sunBarycentricState(const JulianDate& tt);

// Topocentric zenith and azimuth (clockwise from north) of the Sun's centre, with refraction from
// `conditions`. Matches the NREL SPA published example to better than 0.0003 degree (tests/astro).
TopocentricPosition sunPosition(const AstroTime& time, const GeodeticLocation& location,
                                const ObservingConditions& conditions = {});

// Unit vector towards the Sun in the local ENU frame (x east, y north, z up).
glm::dvec3 sunDirectionEnu(const AstroTime& time, const GeodeticLocation& location,
                           const ObservingConditions& conditions = {});

// The Sun's elevation above the horizon (radians, refraction at the standard conditions included) at
// `t_s` seconds after `start`: the clock of a simulation that starts then (the weather model's sun,
// weather/sun_elevation.h). The one sun of every module.
std::function<double(double t_s)> sunElevationAfter(const GeodeticLocation& location, const UtcTime& start);

}  // namespace firmament::astro
