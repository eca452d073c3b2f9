#include "astro/sun.h"

namespace firmament::astro {

BarycentricState sunBarycentricState(const JulianDate& tt) {
  EarthState earth = earthState(tt);
  return {earth.barycentric.position - earth.heliocentric.position,
          earth.barycentric.velocity - earth.heliocentric.velocity};
}

TopocentricPosition sunPosition(const AstroTime& time, const GeodeticLocation& location,
                                const ObservingConditions& conditions) {
  return observe(sunBarycentricState(time.tt), time, location, conditions);
}

glm::dvec3 sunDirectionEnu(const AstroTime& time, const GeodeticLocation& location,
                           const ObservingConditions& conditions) {
  return sunPosition(time, location, conditions).directionEnu();
}

std::function<double(double t_s)> sunElevationAfter(const GeodeticLocation& location, const UtcTime& start) {
  return [location, start](double t_s) {
    return sunPosition(makeAstroTime(addSeconds(start, t_s)), location).elevation();
  };
}

}  // namespace firmament::astro
