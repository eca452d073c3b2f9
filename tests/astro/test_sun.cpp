// Sun position against NREL SPA's published example, and the conventions the renderer relies on.
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "astro/sun.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Reda & Andreas (2008), "Solar Position Algorithm for Solar Radiation Applications", NREL/TP-560-34302,
// Table A4.1 example: 2003-10-17 12:30:30 at UTC-7, 39.742476 N, 105.1786 W, 1830.14 m, 820 mbar, 11 °C,
// ΔT = 67 s. Published topocentric zenith 50.11162° and azimuth 194.34024° (their C code prints 50.111622,
// 194.340241).
struct SpaExample {
  AstroTime time = makeAstroTime("2003-10-17T12:30:30-07:00", 67.0);
  GeodeticLocation place = GeodeticLocation::fromDegrees(39.742476, -105.1786, 1830.14);
  ObservingConditions air{.pressureHpa = 820.0, .temperatureCelsius = 11.0};
  static constexpr double kZenithDeg = 50.111622;
  static constexpr double kAzimuthDeg = 194.340241;
};

TEST(Sun, MatchesSpaPublishedExample) {
  SpaExample spa;
  TopocentricPosition sun = sunPosition(spa.time, spa.place, spa.air);
  double zenithError = sun.zenith / kDegree - SpaExample::kZenithDeg;
  double azimuthError = sun.azimuth / kDegree - SpaExample::kAzimuthDeg;
  std::printf("SPA example: zenith %.6f (error %+.6f deg), azimuth %.6f (error %+.6f deg)\n", sun.zenith / kDegree,
              zenithError, sun.azimuth / kDegree, azimuthError);
  EXPECT_NEAR(sun.zenith / kDegree, SpaExample::kZenithDeg, 0.001);
  EXPECT_NEAR(sun.azimuth / kDegree, SpaExample::kAzimuthDeg, 0.001);
  // The Sun is about 0.9966 au away in mid-October.
  EXPECT_NEAR(sun.distance / 149597870.7e3, 0.9966, 0.001);
}

TEST(Sun, ErfaRefractionModelIsCloseToSpaAtModerateZenith) {
  SpaExample spa;
  ObservingConditions erfaAir = spa.air;
  erfaAir.refraction = RefractionModel::Erfa;
  TopocentricPosition withSpa = sunPosition(spa.time, spa.place, spa.air);
  TopocentricPosition withErfa = sunPosition(spa.time, spa.place, erfaAir);
  std::printf("refraction at zenith 50.1 deg: SPA %.6f deg, ERFA %.6f deg\n",
              (withSpa.geometricZenith - withSpa.zenith) / kDegree,
              (withErfa.geometricZenith - withErfa.zenith) / kDegree);
  EXPECT_NEAR(withSpa.geometricZenith, withErfa.geometricZenith, 1e-12);
  EXPECT_NEAR(withSpa.zenith / kDegree, withErfa.zenith / kDegree, 0.002);
}

TEST(Sun, NoRefractionGivesTheGeometricZenith) {
  SpaExample spa;
  ObservingConditions vacuum = spa.air;
  vacuum.refraction = RefractionModel::None;
  TopocentricPosition sun = sunPosition(spa.time, spa.place, vacuum);
  EXPECT_EQ(sun.zenith, sun.geometricZenith);
  // Refraction lifts the Sun: the apparent zenith is smaller.
  EXPECT_LT(sunPosition(spa.time, spa.place, spa.air).zenith, sun.zenith);
}

TEST(Sun, AzimuthIsClockwiseFromNorth) {
  // Paris-like mid-latitude site at longitude 0 to keep local solar time close to UTC.
  GeodeticLocation place = GeodeticLocation::fromDegrees(48.0, 0.0, 0.0);
  TopocentricPosition morning = sunPosition(makeAstroTime("2021-06-21T07:00:00Z"), place);
  TopocentricPosition noon = sunPosition(makeAstroTime("2021-06-21T12:00:00Z"), place);
  TopocentricPosition evening = sunPosition(makeAstroTime("2021-06-21T17:00:00Z"), place);
  EXPECT_GT(morning.azimuth / kDegree, 45.0);             // east of north...
  EXPECT_LT(morning.azimuth / kDegree, 135.0);            // ...in the eastern quadrant
  EXPECT_NEAR(noon.azimuth / kDegree, 180.0, 3.0);        // due south (equation of time: ~ -1.7 min)
  EXPECT_NEAR(noon.zenith / kDegree, 48.0 - 23.44, 0.2);  // latitude minus solstice declination
  EXPECT_GT(evening.azimuth / kDegree, 225.0);
  EXPECT_LT(evening.azimuth / kDegree, 315.0);
  // In the ENU frame: morning sun has +x (east), noon sun has -y (south), both above the horizon.
  EXPECT_GT(morning.directionEnu().x, 0.5);
  EXPECT_LT(noon.directionEnu().y, -0.4);
  EXPECT_LT(std::abs(noon.directionEnu().x), 0.05);
  EXPECT_GT(noon.directionEnu().z, 0.8);
}

TEST(Sun, SouthernHemisphereNoonSunIsNorth) {
  GeodeticLocation place = GeodeticLocation::fromDegrees(-34.0, 151.0, 0.0);  // Sydney-like
  // Local noon at 151 E is about 01:56 UTC.
  TopocentricPosition noon = sunPosition(makeAstroTime("2021-12-21T01:56:00Z"), place);
  double azimuthDeg = noon.azimuth / kDegree;
  EXPECT_TRUE(azimuthDeg < 20.0 || azimuthDeg > 340.0) << azimuthDeg;
}

TEST(Sun, BelowHorizonAtLocalMidnight) {
  SpaExample spa;
  // Golden, Colorado, local midnight (00:00 at UTC-7) on the same day.
  TopocentricPosition sun = sunPosition(makeAstroTime("2003-10-17T00:00:00-07:00", 67.0), spa.place, spa.air);
  EXPECT_GT(sun.zenith / kDegree, 90.0 + 30.0);
  EXPECT_LT(sun.directionEnu().z, -0.5);
  // Near north at midnight in the northern hemisphere.
  double azimuthDeg = sun.azimuth / kDegree;
  EXPECT_TRUE(azimuthDeg < 30.0 || azimuthDeg > 330.0) << azimuthDeg;
  // No refraction is applied to a Sun far below the horizon.
  EXPECT_EQ(sun.zenith, sun.geometricZenith);
}

TEST(Sun, DirectionIsAUnitVectorMatchingZenithAndAzimuth) {
  SpaExample spa;
  TopocentricPosition sun = sunPosition(spa.time, spa.place, spa.air);
  glm::dvec3 d = sunDirectionEnu(spa.time, spa.place, spa.air);
  EXPECT_NEAR(glm::length(d), 1.0, 1e-15);
  EXPECT_NEAR(std::acos(d.z), sun.zenith, 1e-12);
  EXPECT_NEAR(std::atan2(d.x, d.y) + 2 * std::numbers::pi, sun.azimuth, 1e-12);
}

TEST(Sun, LeapSecondTableAndGivenDeltaTAgree) {
  // In 2003 TAI-UTC was 32 s, so TT-UTC = 64.184 s; SPA's 67 s is TT-UT1 with UT1-UTC ~ -0.3 s plus
  // rounding. The Sun's direction moves only ~0.04"/s along the ecliptic, so both agree closely.
  SpaExample spa;
  AstroTime fromTable = makeAstroTime("2003-10-17T19:30:30Z");
  EXPECT_NEAR(fromTable.deltaT, 64.184, 1e-9);
  TopocentricPosition a = sunPosition(fromTable, spa.place, spa.air);
  TopocentricPosition b = sunPosition(spa.time, spa.place, spa.air);
  EXPECT_NEAR(a.zenith / kDegree, b.zenith / kDegree, 1e-4);
  EXPECT_NEAR(a.azimuth / kDegree, b.azimuth / kDegree, 1e-4);
}

TEST(Refraction, SpaFormulaValues) {
  // At the horizon in the standard SPA atmosphere (1010 mbar, 10 °C) Bennett gives about 0.48 degree
  // (e0 = 0: 1.02 / (60 tan(10.3/5.11 deg)) = 0.4830 deg).
  EXPECT_NEAR(spaRefraction(0.0, 1010.0, 10.0) / kDegree, 0.4830, 5e-4);
  // At the zenith refraction vanishes, and it is zero below the cutoff.
  EXPECT_NEAR(spaRefraction(std::numbers::pi / 2, 1010.0, 10.0) / kDegree, 0.0, 1e-4);
  EXPECT_EQ(spaRefraction(-1.0 * kDegree, 1010.0, 10.0), 0.0);
}

}  // namespace
}  // namespace firmament::astro
