#include "astro/refraction.h"

#include <cmath>
#include <numbers>

namespace firmament::astro {

double spaRefraction(double geometricElevation, double pressureHpa, double temperatureCelsius) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  // Reda & Andreas 2008, §3.14: sun semi-diameter 0.26667° and horizontal refraction 0.5667°.
  constexpr double kLowestElevationDeg = -(0.26667 + 0.5667);
  double e0 = geometricElevation / kDegree;
  if (e0 < kLowestElevationDeg) return 0.0;
  double refractionDeg = (pressureHpa / 1010.0) * (283.0 / (273.0 + temperatureCelsius)) * 1.02 /
                         (60.0 * std::tan((e0 + 10.3 / (e0 + 5.11)) * kDegree));
  return refractionDeg * kDegree;
}

}  // namespace firmament::astro
