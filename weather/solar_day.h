#pragma once
// The fallback analytic sun for the weather model: solar elevation from latitude, day of year and time,
// good to about a degree. The model only takes a function of time, so the integrated build swaps in
// astro's ephemeris without touching the model.
#include <cstdint>
#include <functional>
#include <string>

namespace firmament::weather {

// Sun elevation above the horizon in radians as a function of model time (seconds since the start).
using SunElevationFunction = std::function<double(double t_s)>;

struct UtcTime {
  int year = 2026, month = 6, day = 21;
  double secondsOfDay = 0.0;
  int dayOfYear() const;  // 1 = 1 January
};

// Parses "YYYY-MM-DDThh:mm:ss[.fff]Z"; throws InputError naming the text otherwise.
UtcTime parseUtc(const std::string& text);

// Solar elevation (radians) by the textbook approximation (Cooper 1969 declination; hour angle from mean
// solar time, the equation of time ignored, ≤ 4° error in hour angle):
//   δ = −23.44° cos(2π (N + 10) / 365),  H = 15°/h · (UT + λ/15° − 12 h),
//   sin e = sin φ sin δ + cos φ cos δ cos H.
double analyticSunElevation(double latitude_rad, double longitude_rad, int dayOfYear, double utSeconds);

// The elevation as a function of model time for a start instant and place.
SunElevationFunction analyticSunElevationFunction(double latitude_rad, double longitude_rad, const UtcTime& start);

// Constant elevation (tests: "no sun", "sun at zenith all day").
SunElevationFunction constantSunElevation(double elevation_rad);

}  // namespace firmament::weather
