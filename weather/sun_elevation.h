#pragma once
// The sun the weather model sees: its elevation as a function of model time. The model takes only that
// function, so it depends on no clock or ephemeris; the renderer and the tool give it astro's
// (astro::sunElevationAfter: the ephemeris for the scene's place from the simulation's start), tests
// may give a constant.
#include <functional>

namespace firmament::weather {

// Sun elevation above the horizon in radians as a function of model time (seconds since the start).
using SunElevationFunction = std::function<double(double t_s)>;

// Constant elevation (tests: "no sun", "sun at zenith all day").
inline SunElevationFunction constantSunElevation(double elevation_rad) {
  return [=](double) { return elevation_rad; };
}

}  // namespace firmament::weather
