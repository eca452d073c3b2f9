#pragma once
// Geodetic positions on the WGS84 ellipsoid and the planet-centred (ECEF) and local East-North-Up
// frames built on them (GeographicLib). Angles in radians, lengths in metres.
#include <glm/vec3.hpp>

namespace firmament::astro {

// WGS84 geodetic latitude (north positive), longitude (east positive) and height above the ellipsoid.
struct GeodeticLocation {
  double latitude = 0.0;   // radians
  double longitude = 0.0;  // radians
  double height = 0.0;     // metres

  // Scene files and the command line speak degrees.
  static GeodeticLocation fromDegrees(double latitudeDeg, double longitudeDeg, double heightMetres);
};

// Earth-centred, Earth-fixed Cartesian position (WGS84, metres): x to (0°N, 0°E), z to the north pole.
glm::dvec3 geodeticToEcef(const GeodeticLocation& location);
GeodeticLocation ecefToGeodetic(const glm::dvec3& ecef);

// The local tangent frame at a location: an orthonormal East-North-Up basis expressed in ECEF, with
// `up` along the ellipsoid normal (not towards the Earth's centre), and the origin in ECEF metres.
struct LocalFrame {
  glm::dvec3 origin;
  glm::dvec3 east;
  glm::dvec3 north;
  glm::dvec3 up;

  glm::dvec3 enuToEcefDirection(const glm::dvec3& enu) const { return enu.x * east + enu.y * north + enu.z * up; }
  glm::dvec3 ecefToEnuDirection(const glm::dvec3& ecef) const;
};
LocalFrame localFrame(const GeodeticLocation& location);

// Unit vector in the local ENU frame (x east, y north, z up) for a zenith angle and an azimuth measured
// clockwise from north (north 0, east pi/2), both in radians.
glm::dvec3 enuDirection(double zenith, double azimuth);

}  // namespace firmament::astro
