// WGS84 geodetic <-> ECEF and the local East-North-Up frame.
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <numbers>

#include "astro/geodetic.h"

namespace firmament::astro {
namespace {

constexpr double kWgs84EquatorialRadius = 6378137.0;  // metres, by definition of WGS84
constexpr double kWgs84PolarRadius = 6356752.314245;  // metres, b = a (1 - f), f = 1/298.257223563

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Geodetic, EcefOfKnownPoints) {
  expectNear(geodeticToEcef(GeodeticLocation::fromDegrees(0, 0, 0)), {kWgs84EquatorialRadius, 0, 0}, 1e-6);
  expectNear(geodeticToEcef(GeodeticLocation::fromDegrees(0, 90, 100)), {0, kWgs84EquatorialRadius + 100, 0}, 1e-6);
  expectNear(geodeticToEcef(GeodeticLocation::fromDegrees(90, 0, 0)), {0, 0, kWgs84PolarRadius}, 1e-5);
}

TEST(Geodetic, RoundTrip) {
  GeodeticLocation place = GeodeticLocation::fromDegrees(39.742476, -105.1786, 1830.14);
  GeodeticLocation back = ecefToGeodetic(geodeticToEcef(place));
  EXPECT_NEAR(back.latitude, place.latitude, 1e-12);
  EXPECT_NEAR(back.longitude, place.longitude, 1e-12);
  EXPECT_NEAR(back.height, place.height, 1e-6);
}

TEST(Geodetic, EnuBasisIsOrthonormalAndRightHanded) {
  for (double latitude : {-90.0, -45.0, 0.0, 39.742476, 89.9, 90.0}) {
    for (double longitude : {-180.0, -105.1786, 0.0, 7.98, 135.0}) {
      LocalFrame f = localFrame(GeodeticLocation::fromDegrees(latitude, longitude, 1200.0));
      EXPECT_NEAR(glm::length(f.east), 1.0, 1e-14);
      EXPECT_NEAR(glm::length(f.north), 1.0, 1e-14);
      EXPECT_NEAR(glm::length(f.up), 1.0, 1e-14);
      EXPECT_NEAR(glm::dot(f.east, f.north), 0.0, 1e-14);
      EXPECT_NEAR(glm::dot(f.east, f.up), 0.0, 1e-14);
      EXPECT_NEAR(glm::dot(f.north, f.up), 0.0, 1e-14);
      expectNear(glm::cross(f.east, f.north), f.up, 1e-14);
    }
  }
}

TEST(Geodetic, EnuBasisDirections) {
  LocalFrame f = localFrame(GeodeticLocation::fromDegrees(0, 0, 0));
  expectNear(f.east, {0, 1, 0}, 1e-15);
  expectNear(f.north, {0, 0, 1}, 1e-15);
  expectNear(f.up, {1, 0, 0}, 1e-15);
  expectNear(f.origin, {kWgs84EquatorialRadius, 0, 0}, 1e-6);
  // Up is the ellipsoid normal: at 45° latitude it points 45° above the equatorial plane, not at the
  // geocentre (which would be ~44.81°).
  LocalFrame g = localFrame(GeodeticLocation::fromDegrees(45, 0, 0));
  EXPECT_NEAR(g.up.z, std::sin(std::numbers::pi / 4), 1e-15);
  // Moving along `up` changes only the height.
  GeodeticLocation above = ecefToGeodetic(g.origin + 500.0 * g.up);
  EXPECT_NEAR(above.height, 500.0, 1e-6);
  EXPECT_NEAR(above.latitude, std::numbers::pi / 4, 1e-12);
}

TEST(Geodetic, EnuConversionsInvert) {
  LocalFrame f = localFrame(GeodeticLocation::fromDegrees(46.55, 7.98, 1200));
  glm::dvec3 v = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  expectNear(f.ecefToEnuDirection(f.enuToEcefDirection(v)), v, 1e-15);
}

TEST(Geodetic, EnuDirectionConvention) {
  constexpr double pi = std::numbers::pi;
  expectNear(enuDirection(0.0, 1.0), {0, 0, 1}, 1e-15);
  expectNear(enuDirection(pi / 2, 0.0), {0, 1, 0}, 1e-15);        // north
  expectNear(enuDirection(pi / 2, pi / 2), {1, 0, 0}, 1e-15);     // east: azimuth clockwise from north
  expectNear(enuDirection(pi / 2, pi), {0, -1, 0}, 1e-15);        // south
  expectNear(enuDirection(pi / 2, 1.5 * pi), {-1, 0, 0}, 1e-15);  // west
}

}  // namespace
}  // namespace firmament::astro
