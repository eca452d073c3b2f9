// The star catalogue: xplanet's copy of the Bright Star Catalogue read from the installed package, apparent
// places against ERFA's own eraAtco13, named stars against their Hipparcos places, counts, and the
// photometry (V -> lux, B-V -> colour).
#include <gtest/gtest.h>

#include <erfa.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "astro/star_catalogue.h"
#include "core/error.h"
#include "tests/support/test_paths.h"

namespace firmament::astro {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kArcsecond = kDegree / 3600.0;

const StarCatalogue& catalogue() {
  static const StarCatalogue c = loadStarCatalogue("/usr/share/xplanet/stars/BSC");
  return c;
}

// A place and instant with Orion, Sirius, Canopus low, and Vega, Deneb, Arcturus, Polaris up: La Palma
// (Roque de los Muchachos), 2024-03-01 21:00 UTC.
GeodeticLocation laPalma() { return GeodeticLocation::fromDegrees(28.7606, -17.8816, 2396.0); }
AstroTime testTime() { return makeAstroTime("2024-03-01T21:00:00Z"); }

// eraAtco13 for an ICRS place with space motion; returns the observed ENU direction. phpa = 0 switches
// refraction off.
glm::dvec3 erfaObserved(double ra, double dec, double pmRaCosDecMasYr, double pmDecMasYr, double parallaxMas,
                        double radialVelocityKms, const AstroTime& t, const GeodeticLocation& site, double phpa) {
  constexpr double kMas = kArcsecond / 1000.0;
  double aob = 0, zob = 0, hob = 0, dob = 0, rob = 0, eo = 0;
  const int status =
      eraAtco13(ra, dec, pmRaCosDecMasYr * kMas / std::cos(dec), pmDecMasYr * kMas, parallaxMas / 1000.0,
                radialVelocityKms, t.utcJulian.dayStart, t.utcJulian.dayFraction, 0.0, site.longitude, site.latitude,
                site.height, 0.0, 0.0, phpa, 15.0, 0.0, 0.55, &aob, &zob, &hob, &dob, &rob, &eo);
  EXPECT_GE(status, 0);
  return enuDirection(zob, aob);
}

double separationArcsec(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) / kArcsecond;
}

size_t indexOfHr(int hr) {
  for (size_t i = 0; i < catalogue().stars.size(); ++i)
    if (catalogue().stars[i].brightStarNumber == hr) return i;
  ADD_FAILURE() << "HR " << hr << " not in the catalogue";
  return 0;
}

TEST(StarCatalogue, ReadsEveryStarOfXplanetsBrightStarCatalogue) {
  // xplanet 1.3.1's BSC: 9096 stars (the BSC's 9110 entries less 14 novae and non-stellar objects).
  EXPECT_EQ(catalogue().stars.size(), 9096u);
  const CatalogueStar& sirius = catalogue().stars[indexOfHr(2491)];
  EXPECT_EQ(sirius.name, "9Alp CMa");
  EXPECT_NEAR(sirius.vMagnitude, -1.46, 1e-9);
  EXPECT_NEAR(sirius.declination / kDegree, -16.7161, 1e-9);
  EXPECT_NEAR(sirius.rightAscension / kDegree / 15.0, 6.7525, 1e-9);
  EXPECT_TRUE(std::isnan(sirius.bMinusV));  // xplanet keeps no colours
}

TEST(StarCatalogue, CountBrighterThanSixthMagnitudeMatchesTheFile) {
  // Counted here from the file's third column, independently of the reader, then through the apparent
  // places over the whole sphere (every star comes out once, none lost or duplicated).
  std::ifstream file("/usr/share/xplanet/stars/BSC");
  std::string line;
  int fileCount = 0, fileTotal = 0;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    double dec = 0, ra = 0, v = 0;
    if (!(in >> dec >> ra >> v)) continue;
    ++fileTotal;
    if (v < 6.0) ++fileCount;
  }
  const std::vector<ApparentStar> stars = apparentStars(catalogue(), testTime(), laPalma());
  ASSERT_EQ(int(stars.size()), fileTotal);
  int brighter = 0, aboveHorizon = 0;
  for (const ApparentStar& s : stars) {
    EXPECT_NEAR(glm::length(s.directionEnu), 1.0, 1e-12);
    if (s.illuminanceLux > starIlluminanceLux(6.0)) ++brighter;
    if (s.directionEnu.z > 0.0) ++aboveHorizon;
  }
  std::printf("stars brighter than V 6: %d (file: %d), %d of %d above the horizon\n", brighter, fileCount, aboveHorizon,
              fileTotal);
  EXPECT_EQ(brighter, fileCount);  // 5023
  EXPECT_EQ(fileCount, 5023);
}

TEST(StarCatalogue, ApparentPlacesMatchErfaAtco13OfTheSamePositions) {
  // Our chain (one eraApco context, eraAtciqz, eraAtioq) against ERFA's one-call eraAtco13 on the same
  // catalogue places without space motion: the same algorithms, so agreement to rounding. Geometric
  // (refraction off) for all 9096 stars, then with ERFA's refraction above 10 degrees elevation.
  const AstroTime t = testTime();
  const GeodeticLocation site = laPalma();
  ObservingConditions geometric;
  geometric.refraction = RefractionModel::None;
  const std::vector<ApparentStar> stars = apparentStars(catalogue(), t, site, geometric);
  double worst = 0.0;
  for (const ApparentStar& s : stars) {
    const CatalogueStar& c = catalogue().stars[size_t(s.catalogueIndex)];
    worst = std::max(worst, separationArcsec(s.directionEnu,
                                             erfaObserved(c.rightAscension, c.declination, 0, 0, 0, 0, t, site, 0.0)));
  }
  ObservingConditions erfa;
  erfa.refraction = RefractionModel::Erfa;
  erfa.pressureHpa = 770.0;
  const std::vector<ApparentStar> refracted = apparentStars(catalogue(), t, site, erfa);
  double worstRefracted = 0.0;
  for (const ApparentStar& s : refracted) {
    if (s.directionEnu.z < std::sin(10.0 * kDegree)) continue;
    const CatalogueStar& c = catalogue().stars[size_t(s.catalogueIndex)];
    worstRefracted = std::max(
        worstRefracted,
        separationArcsec(s.directionEnu, erfaObserved(c.rightAscension, c.declination, 0, 0, 0, 0, t, site, 770.0)));
  }
  std::printf("against eraAtco13: worst %.2e\" geometric, %.2e\" with refraction\n", worst, worstRefracted);
  EXPECT_LT(worst, 1e-3);           // measured ~1e-9"
  EXPECT_LT(worstRefracted, 1e-3);  // measured ~1e-9"
}

TEST(StarCatalogue, NamedStarsAreWithinAnArcminuteOfTheirHipparcosPlaces) {
  // Hipparcos (van Leeuwen 2007) ICRS places at J2000 with proper motion, parallax and radial velocity,
  // through eraAtco13 with refraction off: the truth. The catalogue's own error is its rounding
  // (0.0001 h in RA, 0.0001° in Dec: up to 2.7") plus the proper motion it leaves out.
  struct Named {
    const char* name;
    int hr;
    double raHours, decDeg, pmRa, pmDec, parallax, rv;  // mas/yr (pm RA with cos dec), mas, km/s
  };
  const Named named[] = {
      {"Sirius", 2491, 6.0 + 45.0 / 60 + 8.91728 / 3600, -(16.0 + 42.0 / 60 + 58.0171 / 3600), -546.01, -1223.07,
       379.21, -5.5},
      {"Canopus", 2326, 6.0 + 23.0 / 60 + 57.10988 / 3600, -(52.0 + 41.0 / 60 + 44.3810 / 3600), 19.93, 23.24, 10.55,
       20.3},
      {"Vega", 7001, 18.0 + 36.0 / 60 + 56.33635 / 3600, 38.0 + 47.0 / 60 + 1.2802 / 3600, 200.94, 286.23, 130.23,
       -13.9},
      {"Polaris", 424, 2.0 + 31.0 / 60 + 49.09456 / 3600, 89.0 + 15.0 / 60 + 50.7923 / 3600, 44.48, -11.85, 7.54,
       -17.4},
      {"Betelgeuse", 2061, 5.0 + 55.0 / 60 + 10.30536 / 3600, 7.0 + 24.0 / 60 + 25.4304 / 3600, 27.54, 11.30, 6.55,
       21.9},
      {"Rigel", 1713, 5.0 + 14.0 / 60 + 32.27210 / 3600, -(8.0 + 12.0 / 60 + 5.8981 / 3600), 1.31, 0.50, 3.78, 17.8},
      {"Deneb", 7924, 20.0 + 41.0 / 60 + 25.91514 / 3600, 45.0 + 16.0 / 60 + 49.2197 / 3600, 2.01, 1.85, 2.31, -4.5},
      {"Arcturus", 5340, 14.0 + 15.0 / 60 + 39.67207 / 3600, 19.0 + 10.0 / 60 + 56.6730 / 3600, -1093.39, -1999.40,
       88.83, -5.19},
  };
  const AstroTime t = testTime();
  const GeodeticLocation site = laPalma();
  ObservingConditions geometric;
  geometric.refraction = RefractionModel::None;
  const std::vector<ApparentStar> stars = apparentStars(catalogue(), t, site, geometric);
  const double years = (t.tt.value() - 2451545.0) / 365.25;
  for (const Named& n : named) {
    const ApparentStar& s = stars[indexOfHr(n.hr)];
    const glm::dvec3 truth =
        erfaObserved(n.raHours * 15.0 * kDegree, n.decDeg * kDegree, n.pmRa, n.pmDec, n.parallax, n.rv, t, site, 0.0);
    const double error = separationArcsec(s.directionEnu, truth);
    const double properMotion = std::hypot(n.pmRa, n.pmDec) / 1000.0 * years;
    std::printf("%-10s error %5.1f\" (proper motion since J2000 %5.1f\")\n", n.name, error, properMotion);
    EXPECT_LT(error, 60.0) << n.name;
    // The error is the missing proper motion to within the catalogue's rounding (3") and parallax (<0.4").
    EXPECT_NEAR(error, properMotion, 4.0) << n.name;
  }
}

TEST(StarCatalogue, RefractionFollowsTheConditions) {
  // The default (SPA's formula) lifts a star by the formula's amount; none leaves the geometric place.
  const std::vector<ApparentStar> spa = apparentStars(catalogue(), testTime(), laPalma());
  ObservingConditions none;
  none.refraction = RefractionModel::None;
  const std::vector<ApparentStar> geometric = apparentStars(catalogue(), testTime(), laPalma(), none);
  int checked = 0;
  for (size_t i = 0; i < spa.size(); ++i) {
    EXPECT_DOUBLE_EQ(spa[i].geometricZenith, geometric[i].zenith);
    const double elevation = std::numbers::pi / 2 - spa[i].geometricZenith;
    if (elevation < -1.0 * kDegree) {
      EXPECT_DOUBLE_EQ(spa[i].zenith, spa[i].geometricZenith);
      continue;
    }
    EXPECT_NEAR(spa[i].geometricZenith - spa[i].zenith, spaRefraction(elevation, 1013.25, 15.0), 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 3000);
}

TEST(StarCatalogue, ZeroMagnitudeIlluminanceAndMagnitudeScale) {
  EXPECT_DOUBLE_EQ(starIlluminanceLux(0.0), 2.54e-6);
  // 5 magnitudes are a factor 100; V = -13.99 - 2.5 log10(E / lx) (Allen 1973) to 0.005 mag.
  EXPECT_NEAR(starIlluminanceLux(5.0) / starIlluminanceLux(0.0), 0.01, 1e-15);
  EXPECT_NEAR(-13.99 - 2.5 * std::log10(starIlluminanceLux(1.0)), 1.0, 0.005);
}

TEST(StarCatalogue, BallesterosTemperaturesAndBlackbodyColours) {
  // Ballesteros (2012) eq. 14 at B-V = 0.65 (the Sun, Ramirez et al. 2012: 0.653): 5778 K (T_sun 5772 K).
  EXPECT_NEAR(starTemperatureFromBMinusV(0.65), 4600.0 * (1.0 / (0.92 * 0.65 + 1.7) + 1.0 / (0.92 * 0.65 + 0.62)),
              1e-9);
  EXPECT_NEAR(starTemperatureFromBMinusV(0.65), 5772.0, 40.0);
  // Vega (B-V 0.00) ~ 9600 K: the fit gives 10 125 K; Betelgeuse (1.85) ~ 3600 K: 3 334 K (the fit's range
  // ends at 2.0). Colour order: a hot star is bluer than a cool one; every colour has luminance 1.
  EXPECT_NEAR(starTemperatureFromBMinusV(0.0), 10125.2, 1.0);
  const glm::dvec3 hot = blackbodyRec709UnitLuminance(starTemperatureFromBMinusV(-0.3));
  const glm::dvec3 cool = blackbodyRec709UnitLuminance(starTemperatureFromBMinusV(1.85));
  EXPECT_NEAR(0.2126 * hot.x + 0.7152 * hot.y + 0.0722 * hot.z, 1.0, 1e-12);
  EXPECT_GT(hot.z / hot.x, 1.0);
  EXPECT_LT(cool.z / cool.x, 0.5);
  // A 6504 K blackbody is near D65 (Rec.709 white): within 5 % per channel.
  const glm::dvec3 white = blackbodyRec709UnitLuminance(6504.0);
  EXPECT_NEAR(white.x, 1.0, 0.05);
  EXPECT_NEAR(white.y, 1.0, 0.05);
  EXPECT_NEAR(white.z, 1.0, 0.1);
}

TEST(StarCatalogue, MissingOrMalformedFilesAreInputErrorsNamingTheFile) {
  try {
    loadStarCatalogue("/nonexistent/BSC");
    FAIL();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("/nonexistent/BSC"), std::string::npos) << message;
    EXPECT_NE(message.find("xplanet"), std::string::npos) << message;
    EXPECT_NE(message.find("FIRMAMENT_STAR_CATALOGUE"), std::string::npos) << message;
  }
  const std::filesystem::path dir = test::scratchDir("star_catalogue");
  const std::map<std::string, std::string> bad = {
      {"dec.txt", "# header\n 12.0 1.0 2.0 \"a\" 1\n 95.0 1.0 2.0 \"b\" 2\n"},
      {"ra.txt", " 12.0 25.0 2.0\n"},
      {"mag.txt", " 12.0 1.0 bright\n"},
      {"quote.txt", " 12.0 1.0 2.0 \"open\n"},
      {"empty.txt", "# nothing\n\n"},
  };
  const std::map<std::string, std::string> expected = {
      {"dec.txt", "line 3: declination 95 is out of range; allowed: -90 to 90 degrees"},
      {"ra.txt", "line 1: right ascension 25 is out of range; allowed: 0 to 24 hours"},
      {"mag.txt", "line 1: missing or unreadable V magnitude"},
      {"quote.txt", "line 1: unterminated quoted name"},
      {"empty.txt", "holds no star"},
  };
  for (const auto& [name, text] : bad) {
    std::ofstream(dir / name) << text;
    try {
      loadStarCatalogue(dir / name);
      ADD_FAILURE() << name;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find((dir / name).string()), std::string::npos) << message;
      EXPECT_NE(message.find(expected.at(name)), std::string::npos) << message;
    }
  }
}

TEST(StarCatalogue, EnvironmentVariableChoosesTheFile) {
  const std::filesystem::path dir = test::scratchDir("star_catalogue_env");
  std::ofstream(dir / "two.txt") << " 10.0 1.0 1.5 \"x\" 1\n-10.0 2.0 3.5\n";
  setenv("FIRMAMENT_STAR_CATALOGUE", (dir / "two.txt").c_str(), 1);
  EXPECT_EQ(defaultStarCataloguePath(), dir / "two.txt");
  EXPECT_EQ(loadDefaultStarCatalogue().stars.size(), 2u);
  unsetenv("FIRMAMENT_STAR_CATALOGUE");
  EXPECT_EQ(defaultStarCataloguePath(), std::filesystem::path("/usr/share/xplanet/stars/BSC"));
}

}  // namespace
}  // namespace firmament::astro
