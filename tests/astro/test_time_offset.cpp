// UTC arithmetic for simulated time: day, month, year and leap-year rollovers.
#include <gtest/gtest.h>

#include "astro/time.h"

namespace firmament::astro {
namespace {

TEST(UtcArithmetic, RollsOverDaysMonthsYearsAndLeapDays) {
  UtcTime t = addSeconds(parseUtc("2026-12-31T23:30:00Z"), 3600.0);
  EXPECT_EQ(formatUtc(t).substr(0, 19), "2027-01-01T00:30:00");
  t = addSeconds(parseUtc("2024-02-28T12:00:00Z"), 86400.0);
  EXPECT_EQ(t.month, 2);
  EXPECT_EQ(t.day, 29);
  t = addSeconds(parseUtc("2026-03-01T00:00:10Z"), -20.0);
  EXPECT_EQ(formatUtc(t).substr(0, 19), "2026-02-28T23:59:50");
  t = addSeconds(parseUtc("2026-06-21T15:30:00Z"), 0.25);
  EXPECT_NEAR(t.second, 0.25, 1e-9);
}

TEST(UtcArithmetic, SunFollowsTheOffsetTime) {
  // An offset of whole days changes the Julian date by exactly that many days.
  AstroTime a = makeAstroTime(parseUtc("2026-06-21T15:30:00Z"));
  AstroTime b = makeAstroTime(addSeconds(parseUtc("2026-06-21T15:30:00Z"), 3.0 * 86400.0));
  EXPECT_NEAR(b.utcJulian.value() - a.utcJulian.value(), 3.0, 1e-9);
}

}  // namespace
}  // namespace firmament::astro
