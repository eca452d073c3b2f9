#include "terrain/terrain_frame.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <limits>

namespace firmament::terrain {
namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;
}

TerrainFrame::TerrainFrame(const astro::GeodeticLocation& location, double planetRadius)
    : location_(location), planetRadius_(planetRadius) {}

glm::dvec2 TerrainFrame::planeToGeodetic(glm::dvec2 plane) const {
  const double rho = std::hypot(plane.x, plane.y);
  const double theta = std::atan2(rho, planetRadius_);
  const double s = planetRadius_ * theta;  // geodesic distance from the location
  const double scale = rho > 0.0 ? s / rho : 1.0;
  static const GeographicLib::AzimuthalEquidistant projection(GeographicLib::Geodesic::WGS84());
  double lat = 0.0, lon = 0.0, azimuth = 0.0, rk = 0.0;
  projection.Reverse(location_.latitude / kDegree, location_.longitude / kDegree, plane.x * scale, plane.y * scale, lat,
                     lon, azimuth, rk);
  return {lat * kDegree, lon * kDegree};
}

glm::dvec2 TerrainFrame::geodeticToPlane(glm::dvec2 latitudeLongitude) const {
  static const GeographicLib::AzimuthalEquidistant projection(GeographicLib::Geodesic::WGS84());
  double east = 0.0, north = 0.0, azimuth = 0.0, rk = 0.0;
  projection.Forward(location_.latitude / kDegree, location_.longitude / kDegree, latitudeLongitude.x / kDegree,
                     latitudeLongitude.y / kDegree, east, north, azimuth, rk);
  const double s = std::hypot(east, north);
  const double theta = s / planetRadius_;
  if (!(theta < kMaxTerrainAngle)) return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
  const double scale = s > 0.0 ? planetRadius_ * std::tan(theta) / s : 1.0;
  return {east * scale, north * scale};
}

glm::dvec2 TerrainFrame::planeOfDirection(const glm::dvec3& d) const {
  if (!(d.z > 0.0)) return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
  return {planetRadius_ * d.x / d.z, planetRadius_ * d.y / d.z};
}

glm::dvec3 TerrainFrame::directionOfPlane(glm::dvec2 plane) const {
  return glm::normalize(glm::dvec3(plane.x, plane.y, planetRadius_));
}

}  // namespace firmament::terrain
