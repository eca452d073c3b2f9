// UTC parsing and time scales.
#include <gtest/gtest.h>

#include <string>

#include "astro/time.h"
#include "core/error.h"

namespace firmament::astro {
namespace {

TEST(Time, ParsesZuluTime) {
  UtcTime t = parseUtc("2003-10-17T19:30:30Z");
  EXPECT_EQ(t.year, 2003);
  EXPECT_EQ(t.month, 10);
  EXPECT_EQ(t.day, 17);
  EXPECT_EQ(t.hour, 19);
  EXPECT_EQ(t.minute, 30);
  EXPECT_DOUBLE_EQ(t.second, 30.0);
}

TEST(Time, ParsesFractionalSeconds) {
  EXPECT_NEAR(parseUtc("2003-10-17T19:30:30.125Z").second, 30.125, 1e-12);
  EXPECT_NEAR(parseUtc("2003-10-17T19:30:30.5Z").second, 30.5, 1e-12);
}

TEST(Time, AppliesOffsets) {
  UtcTime t = parseUtc("2003-10-17T12:30:30-07:00");
  EXPECT_EQ(t.day, 17);
  EXPECT_EQ(t.hour, 19);
  EXPECT_EQ(t.minute, 30);
  // Crossing midnight and a month and year boundary.
  UtcTime u = parseUtc("2021-01-01T01:15:00+05:30");
  EXPECT_EQ(u.year, 2020);
  EXPECT_EQ(u.month, 12);
  EXPECT_EQ(u.day, 31);
  EXPECT_EQ(u.hour, 19);
  EXPECT_EQ(u.minute, 45);
  UtcTime v = parseUtc("2020-02-28T22:00:00-0300");  // basic offset form, leap year
  EXPECT_EQ(v.month, 2);
  EXPECT_EQ(v.day, 29);
  EXPECT_EQ(v.hour, 1);
}

TEST(Time, AcceptsRealLeapSecondOnly) {
  EXPECT_NO_THROW(parseUtc("2016-12-31T23:59:60.5Z"));
  EXPECT_THROW(parseUtc("2017-12-31T23:59:60Z"), InputError);
}

TEST(Time, RejectsMalformedText) {
  for (const char* bad : {"", "2003-10-17", "2003-10-17 19:30:30Z", "2003-10-17T19:30:30", "2003-10-17T19:30Z",
                          "03-10-17T19:30:30Z", "2003-13-17T19:30:30Z", "2003-02-30T19:30:30Z", "2003-10-17T24:00:00Z",
                          "2003-10-17T19:60:00Z", "2003-10-17T19:30:30.Z", "2003-10-17T19:30:30ZZ",
                          "2003-10-17T19:30:30+7", "2003-10-17T19:30:30+07:60", "noon"}) {
    EXPECT_THROW(parseUtc(bad), InputError) << bad;
  }
}

TEST(Time, ErrorNamesTheExpectedForm) {
  try {
    parseUtc("2003-10-17 19:30:30");
    FAIL() << "no error";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("YYYY-MM-DDThh:mm:ss"), std::string::npos) << message;
    EXPECT_NE(message.find("2003-10-17 19:30:30"), std::string::npos) << message;
  }
}

TEST(Time, JulianDates) {
  // J2000.0 = 2000-01-01T12:00:00 TT = JD 2451545.0; in UTC that is 11:58:55.816.
  AstroTime j2000 = makeAstroTime("2000-01-01T11:58:55.816Z");
  EXPECT_NEAR(j2000.tt.value(), 2451545.0, 1e-8);
  EXPECT_NEAR(j2000.deltaT, 32.0 + 32.184, 1e-9);  // TAI-UTC was 32 s in 2000
  // Meeus (1998) example 7.a: 1957 October 4.81 = JD 2436116.31.
  AstroTime sputnik = makeAstroTime("1957-10-04T19:26:24Z");
  EXPECT_NEAR(sputnik.utcJulian.value(), 2436116.31, 1e-8);
  // A given ΔT wins over the table, and TT - UT1 equals it.
  AstroTime spa = makeAstroTime("2003-10-17T19:30:30Z", 67.0);
  EXPECT_NEAR((spa.tt.value() - spa.ut1.value()) * 86400.0, 67.0, 1e-4);
  EXPECT_NEAR(spa.ut1.value(), 2452930.312847, 1e-6);  // SPA's printed JD
}

TEST(Time, DeltaTBefore1960UsesTheLongTermFormula) {
  // Morrison & Stephenson: ΔT(1900) = -20 + 32 * 0.8^2 = 0.48 s.
  EXPECT_NEAR(makeAstroTime("1900-01-01T00:00:00Z").deltaT, 0.48, 0.05);
}

TEST(Time, FormatsBack) { EXPECT_EQ(formatUtc(parseUtc("2003-10-17T12:30:30.25-07:00")), "2003-10-17T19:30:30.250Z"); }

}  // namespace
}  // namespace firmament::astro
