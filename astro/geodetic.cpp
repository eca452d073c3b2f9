#include "astro/geodetic.h"

#include <GeographicLib/Geocentric.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <vector>

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

const GeographicLib::Geocentric& wgs84() { return GeographicLib::Geocentric::WGS84(); }

}  // namespace

GeodeticLocation GeodeticLocation::fromDegrees(double latitudeDeg, double longitudeDeg, double heightMetres) {
  return {latitudeDeg * kDegree, longitudeDeg * kDegree, heightMetres};
}

glm::dvec3 geodeticToEcef(const GeodeticLocation& location) {
  glm::dvec3 p;
  wgs84().Forward(location.latitude / kDegree, location.longitude / kDegree, location.height, p.x, p.y, p.z);
  return p;
}

GeodeticLocation ecefToGeodetic(const glm::dvec3& ecef) {
  double latitude = 0.0, longitude = 0.0, height = 0.0;
  wgs84().Reverse(ecef.x, ecef.y, ecef.z, latitude, longitude, height);
  return GeodeticLocation::fromDegrees(latitude, longitude, height);
}

glm::dvec3 LocalFrame::ecefToEnuDirection(const glm::dvec3& ecef) const {
  return {glm::dot(ecef, east), glm::dot(ecef, north), glm::dot(ecef, up)};
}

LocalFrame localFrame(const GeodeticLocation& location) {
  // GeographicLib returns the ENU -> ECEF rotation as a row-major 3x3 matrix M (Geocentric::Forward):
  // its columns are the east, north and up unit vectors expressed in ECEF.
  std::vector<double> m(9);
  LocalFrame frame;
  wgs84().Forward(location.latitude / kDegree, location.longitude / kDegree, location.height, frame.origin.x,
                  frame.origin.y, frame.origin.z, m);
  frame.east = {m[0], m[3], m[6]};
  frame.north = {m[1], m[4], m[7]};
  frame.up = {m[2], m[5], m[8]};
  return frame;
}

glm::dvec3 enuDirection(double zenith, double azimuth) {
  double sinZenith = std::sin(zenith);
  return {sinZenith * std::sin(azimuth), sinZenith * std::cos(azimuth), std::cos(zenith)};
}

}  // namespace firmament::astro
