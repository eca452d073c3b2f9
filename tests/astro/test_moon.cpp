// The Moon against Meeus (1998), Astronomical Algorithms, 2nd ed., examples 47.a and 48.a.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "astro/moon.h"
#include "astro/sun.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// 1992 April 12, 0h TD (= TT). Given as UTC with ΔT chosen so that TT is exactly 0h.
AstroTime meeusEpoch() { return makeAstroTime("1992-04-11T23:59:00Z", 60.0); }

TEST(Moon, MatchesMeeusExample47a) {
  // Meeus example 47.a: geometric λ = 133.162655°, β = -3.229126°, Δ = 368409.7 km, referred to the
  // mean equinox of date (the apparent λ adds Δψ = +0.004610°). eraMoon98 implements the same series
  // without Meeus's light-time term (~0.7"), and is good to 2.9" RMS, 18" worst against ELP/MPP02.
  AstroTime t = meeusEpoch();
  EXPECT_NEAR(t.tt.value(), 2448724.5, 1e-9);
  EclipticPosition moon = moonGeocentricEcliptic(t);
  double dLongitude = moon.longitude / kDegree - 133.162655;
  double dLatitude = moon.latitude / kDegree - (-3.229126);
  double dDistance = moon.distance / 1000.0 - 368409.7;
  std::printf("Moon vs Meeus 47.a: dLambda %+.2f\", dBeta %+.2f\", dDistance %+.2f km\n", dLongitude * 3600,
              dLatitude * 3600, dDistance);
  EXPECT_NEAR(moon.longitude / kDegree, 133.162655, 2.0 / 3600);
  EXPECT_NEAR(moon.latitude / kDegree, -3.229126, 2.0 / 3600);
  EXPECT_NEAR(moon.distance / 1000.0, 368409.7, 1.0);
}

TEST(Moon, PhaseMatchesMeeusExample48a) {
  // Meeus example 48.a, same instant: illuminated fraction k = 0.6786 (phase angle i = 69.0756°),
  // waxing (first quarter was 1992 April 10).
  MoonPhase phase = moonPhase(meeusEpoch());
  std::printf("Moon phase vs Meeus 48.a: k %.5f (0.6786), i %.4f deg (69.0756)\n", phase.illuminatedFraction,
              phase.phaseAngle / kDegree);
  EXPECT_NEAR(phase.illuminatedFraction, 0.6786, 1e-4);
  EXPECT_NEAR(phase.phaseAngle / kDegree, 69.0756, 0.01);
  EXPECT_TRUE(phase.waxing);
}

TEST(Moon, FullAndNewMoon) {
  // Full Moon 2021-05-26 11:14 UTC (total lunar eclipse); new Moon 2021-06-10 10:53 UTC (annular eclipse).
  MoonPhase full = moonPhase(makeAstroTime("2021-05-26T11:14:00Z"));
  MoonPhase fresh = moonPhase(makeAstroTime("2021-06-10T10:53:00Z"));
  EXPECT_GT(full.illuminatedFraction, 0.999);
  EXPECT_LT(fresh.illuminatedFraction, 0.001);
  EXPECT_FALSE(moonPhase(makeAstroTime("2021-05-30T00:00:00Z")).waxing);
  EXPECT_TRUE(moonPhase(makeAstroTime("2021-05-20T00:00:00Z")).waxing);
}

TEST(Moon, TopocentricParallax) {
  // The Moon's horizontal parallax is ~1°: seen from the ground it is lower than from the geocentre.
  AstroTime t = meeusEpoch();
  ObservingConditions vacuum{.refraction = RefractionModel::None};
  TopocentricPosition ground = moonPosition(t, GeodeticLocation::fromDegrees(0, 0, 0), vacuum);
  EXPECT_GT(ground.distance, 360000e3);
  EXPECT_LT(ground.distance, 375000e3);
  // During a total solar eclipse the Sun and Moon coincide topocentrically: 2017-08-21, 18:25:30 UTC
  // at 36.97 N, 87.67 W (greatest eclipse, Hopkinsville, Kentucky).
  AstroTime eclipse = makeAstroTime("2017-08-21T18:25:30Z");
  GeodeticLocation place = GeodeticLocation::fromDegrees(36.97, -87.67, 0);
  glm::dvec3 sun = sunPosition(eclipse, place, vacuum).directionEnu();
  glm::dvec3 moon = moonPosition(eclipse, place, vacuum).directionEnu();
  double separationDeg = std::acos(std::fmin(1.0, sun.x * moon.x + sun.y * moon.y + sun.z * moon.z)) / kDegree;
  EXPECT_LT(separationDeg, 0.02);  // the discs are ~0.5° across
}

}  // namespace
}  // namespace firmament::astro
