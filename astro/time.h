#pragma once
// Time for astronomy: civil UTC as the user writes it, and the Julian dates (UTC, UT1, TT) that the
// ERFA routines take. See docs/astro.md for the conventions.
#include <optional>
#include <string>
#include <string_view>

namespace firmament::astro {

// A calendar instant in UTC. `second` may reach 60.x on a day with a leap second.
struct UtcTime {
  int year = 2000;
  int month = 1;
  int day = 1;
  int hour = 12;
  int minute = 0;
  double second = 0.0;
};

// Parses ISO 8601 "YYYY-MM-DDThh:mm:ss[.fff]Z" or the same with a "+hh:mm"/"-hh:mm" offset from UTC
// (local time = UTC + offset, so "12:30:30-07:00" is 19:30:30 UTC). Throws InputError naming the
// expected form when the text does not match or a field is out of range.
UtcTime parseUtc(std::string_view text);

// "YYYY-MM-DDThh:mm:ss.sssZ".
std::string formatUtc(const UtcTime& utc);

// `utc` plus `seconds` (may be negative), counting every day as 86400 s (a leap second inside the
// interval is not counted; simulated-time offsets never need that precision).
UtcTime addSeconds(const UtcTime& utc, double seconds);

// A Julian date split in two parts, as ERFA takes it: `dayStart + dayFraction` is the date. Splitting
// keeps the time of day at full double precision (a single double JD resolves only ~20 µs).
struct JulianDate {
  double dayStart = 0.0;
  double dayFraction = 0.0;
  double value() const { return dayStart + dayFraction; }
};

// The time scales one instant needs. UT1 drives Earth rotation; TT drives the ephemerides.
struct AstroTime {
  UtcTime utc;
  JulianDate utcJulian;  // ERFA "quasi" JD for UTC (a leap-second day is 86401 s long)
  JulianDate ut1;        // UT1, taken equal to UTC (|UT1 - UTC| < 0.9 s by the definition of UTC)
  JulianDate tt;         // Terrestrial Time
  double deltaT = 0.0;   // TT - UT1, seconds
};

// Builds the time scales for `utc`. With `deltaTSeconds` (TT - UT1) given, TT = UT1 + deltaT, as NREL
// SPA does. Otherwise TT = UTC + (TAI - UTC) + 32.184 s from ERFA's leap-second table (eraDat); before
// 1960, where UTC is undefined, Morrison & Stephenson's (2004) long-term parabola gives deltaT.
AstroTime makeAstroTime(const UtcTime& utc, std::optional<double> deltaTSeconds = std::nullopt);

// Convenience: parseUtc then makeAstroTime.
AstroTime makeAstroTime(std::string_view iso8601, std::optional<double> deltaTSeconds = std::nullopt);

}  // namespace firmament::astro
