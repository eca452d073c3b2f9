#include "weather/solar_day.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.h"

namespace firmament::weather {

int UtcTime::dayOfYear() const {
  static const int cumulative[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return cumulative[month - 1] + day + (leap && month > 2 ? 1 : 0);
}

UtcTime parseUtc(const std::string& text) {
  UtcTime t;
  int hour = 0, minute = 0, consumed = 0;
  double second = 0.0;
  int n = std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%n", &t.year, &t.month, &t.day, &hour, &minute,
                      &second, &consumed);
  bool ok = n == 6 && consumed > 0 && size_t(consumed) + 1 == text.size() && text.back() == 'Z' &&
            t.month >= 1 && t.month <= 12 && t.day >= 1 && t.day <= 31 && hour >= 0 && hour <= 23 &&
            minute >= 0 && minute <= 59 && second >= 0.0 && second < 61.0;
  if (!ok) throw InputError("time '" + text + "' is not UTC ISO 8601 (YYYY-MM-DDThh:mm:ss[.fff]Z)");
  t.secondsOfDay = hour * 3600.0 + minute * 60.0 + second;
  return t;
}

double analyticSunElevation(double latitude_rad, double longitude_rad, int dayOfYear, double utSeconds) {
  constexpr double pi = std::numbers::pi;
  double declination = -23.44 * pi / 180.0 * std::cos(2.0 * pi * (dayOfYear + 10) / 365.0);
  double solarHours = utSeconds / 3600.0 + longitude_rad * 12.0 / pi;
  double hourAngle = (solarHours - 12.0) * pi / 12.0;
  double s = std::sin(latitude_rad) * std::sin(declination) +
             std::cos(latitude_rad) * std::cos(declination) * std::cos(hourAngle);
  return std::asin(std::fmax(-1.0, std::fmin(1.0, s)));
}

SunElevationFunction analyticSunElevationFunction(double latitude_rad, double longitude_rad, const UtcTime& start) {
  int day0 = start.dayOfYear();
  double sec0 = start.secondsOfDay;
  return [=](double t_s) {
    double total = sec0 + t_s;
    double days = std::floor(total / 86400.0);
    return analyticSunElevation(latitude_rad, longitude_rad, day0 + int(days), total - days * 86400.0);
  };
}

SunElevationFunction constantSunElevation(double elevation_rad) {
  return [=](double) { return elevation_rad; };
}

}  // namespace firmament::weather
