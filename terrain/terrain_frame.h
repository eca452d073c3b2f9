#pragma once
// Where a height field lies on the Earth: the gnomonic plane of the renderer's sphere, tangent at the
// scene's location, tied to geodetic (WGS84) latitude and longitude.
//
// The renderer's planet is a sphere of radius R (the atmosphere's ground radius) with the scene's
// location on its +z axis; the height field's plane point (x, y) is the sphere's direction
// normalize(x, y, R) (shaders/common/terrain_geometry.glsl): the angle θ = atan(√(x² + y²) / R) from
// the location along the azimuth φ = atan2(x, y) (clockwise from north). That direction is tied to the
// WGS84 point at geodesic distance s = R θ from the location along the same azimuth (GeographicLib's
// azimuthal equidistant projection, Karney 2013, "Algorithms for geodesics", J. Geodesy 87:43–55): the
// sphere's ground distances and azimuths from the location are the ellipsoid's, exactly, and a raster
// in any coordinate system lands where it belongs as seen from the location. Away from the location
// the plane's scale differs from the ground's by the gnomonic factor (1/cos²θ radially, +0.025 % at
// 100 km) and shapes shear by the ellipsoid's flattening (< 0.34 %), both well below a DEM's pixel at
// the extents a scene sees.
#include <glm/glm.hpp>

#include "astro/geodetic.h"

namespace firmament::terrain {

// The largest angle from the location that a terrain may reach (60°: 11 000 km of plane at Earth's
// radius); beyond it the gnomonic plane stretches too much to be useful.
inline constexpr double kMaxTerrainAngle = 1.0471975511965976;

class TerrainFrame {
 public:
  TerrainFrame(const astro::GeodeticLocation& location, double planetRadius);

  const astro::GeodeticLocation& location() const { return location_; }
  double planetRadius() const { return planetRadius_; }

  // The geodetic (latitude, longitude) in radians of the ground under the plane point (x, y) metres.
  glm::dvec2 planeToGeodetic(glm::dvec2 plane) const;
  // The plane point of a geodetic (latitude, longitude) in radians; the inverse of planeToGeodetic.
  // Points more than kMaxTerrainAngle from the location come back as NaN.
  glm::dvec2 geodeticToPlane(glm::dvec2 latitudeLongitude) const;

  // The plane point of a direction / the unit direction of a plane point (planet-centred, ENU axes).
  glm::dvec2 planeOfDirection(const glm::dvec3& direction) const;
  glm::dvec3 directionOfPlane(glm::dvec2 plane) const;

 private:
  astro::GeodeticLocation location_;
  double planetRadius_;
};

}  // namespace firmament::terrain
