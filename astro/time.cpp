#include "astro/time.h"

#include <erfa.h>

#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace firmament::astro {
namespace {

constexpr double kSecondsPerDay = 86400.0;
// TT - TAI, exactly, by the definition of TT (IAU 1991 Resolution A4).
constexpr double kTTMinusTAI = 32.184;

[[noreturn]] void fail(std::string_view text, const std::string& problem) {
  throw InputError("UTC time '" + std::string(text) + "': " + problem +
                   "; expected ISO 8601 'YYYY-MM-DDThh:mm:ss[.fff]Z' or with an offset '+hh:mm'/'-hh:mm' "
                   "instead of 'Z' (e.g. 2003-10-17T19:30:30Z or 2003-10-17T12:30:30-07:00)");
}

// A cursor over the text that reads fixed-width fields and names what it expected on failure.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  int digits(int count, const char* what) {
    int value = 0;
    for (int i = 0; i < count; ++i) {
      if (pos_ >= text_.size() || !std::isdigit(static_cast<unsigned char>(text_[pos_])))
        fail(text_, std::string("expected ") + std::to_string(count) + " digits for the " + what + " at position " +
                        std::to_string(pos_ + 1 - i));
      value = value * 10 + (text_[pos_++] - '0');
    }
    return value;
  }
  void literal(char c, const char* what) {
    if (pos_ >= text_.size() || text_[pos_] != c)
      fail(text_, std::string("expected '") + c + "' " + what + " at position " + std::to_string(pos_ + 1));
    ++pos_;
  }
  bool accept(char c) {
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // Digits after a decimal point, as a fraction in [0, 1).
  double fraction() {
    double value = 0.0, scale = 0.1;
    size_t start = pos_;
    while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) {
      value += (text_[pos_++] - '0') * scale;
      scale *= 0.1;
    }
    if (pos_ == start) fail(text_, "expected digits after the decimal point of the seconds");
    return value;
  }
  bool done() const { return pos_ == text_.size(); }
  size_t position() const { return pos_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
};

// Morrison & Stephenson (2004), "Historical values of the Earth's clock error ΔT", J. Hist. Astron.
// 35, 327: ΔT ≈ -20 + 32 u² seconds, u = (year - 1820) / 100. Only used before UTC existed (1960),
// where a few tens of seconds of error move the Sun by under an arcsecond.
double longTermDeltaT(double year) {
  double u = (year - 1820.0) / 100.0;
  return -20.0 + 32.0 * u * u;
}

}  // namespace

UtcTime parseUtc(std::string_view text) {
  Scanner s(text);
  UtcTime t;
  t.year = s.digits(4, "year");
  s.literal('-', "after the year");
  t.month = s.digits(2, "month");
  s.literal('-', "after the month");
  t.day = s.digits(2, "day");
  s.literal('T', "between date and time");
  t.hour = s.digits(2, "hour");
  s.literal(':', "after the hour");
  t.minute = s.digits(2, "minute");
  s.literal(':', "after the minute");
  t.second = s.digits(2, "second");
  if (s.accept('.')) t.second += s.fraction();

  int offsetMinutes = 0;
  if (!s.accept('Z')) {
    int sign = s.accept('+') ? 1 : (s.accept('-') ? -1 : 0);
    if (sign == 0)
      fail(text, "expected 'Z' or a '+hh:mm'/'-hh:mm' offset at position " + std::to_string(s.position() + 1));
    int hours = s.digits(2, "offset hours");
    s.accept(':');  // ISO 8601 allows both +hh:mm and +hhmm
    int minutes = s.digits(2, "offset minutes");
    if (hours > 23 || minutes > 59) fail(text, "offset out of range (at most 23:59)");
    offsetMinutes = sign * (hours * 60 + minutes);
  }
  if (!s.done()) fail(text, "unexpected text after the time zone at position " + std::to_string(s.position() + 1));

  if (t.month < 1 || t.month > 12) fail(text, "month " + std::to_string(t.month) + " is not in 1..12");
  double mjd0 = 0.0, mjd = 0.0;
  if (eraCal2jd(t.year, t.month, t.day, &mjd0, &mjd) != 0)
    fail(text, "day " + std::to_string(t.day) + " does not exist in that month");
  if (t.hour > 23) fail(text, "hour " + std::to_string(t.hour) + " is not in 0..23");
  if (t.minute > 59) fail(text, "minute " + std::to_string(t.minute) + " is not in 0..59");
  if (t.second >= 61.0) fail(text, "second is not below 61");

  // Move local clock time to UTC by whole minutes; the seconds (including a leap second 60.x) stay.
  if (offsetMinutes != 0) {
    int minuteOfDay = t.hour * 60 + t.minute - offsetMinutes;
    int dayShift = int(std::floor(minuteOfDay / 1440.0));
    minuteOfDay -= dayShift * 1440;
    double fractionOfDay = 0.0;
    if (eraJd2cal(mjd0, mjd + dayShift, &t.year, &t.month, &t.day, &fractionOfDay) != 0)
      fail(text, "date out of range");
    t.hour = minuteOfDay / 60;
    t.minute = minuteOfDay % 60;
  }

  // ERFA knows which days have leap seconds: second 60 on any other day is an error.
  double jd1 = 0.0, jd2 = 0.0;
  int status = eraDtf2d("UTC", t.year, t.month, t.day, t.hour, t.minute, t.second, &jd1, &jd2);
  if (status < 0) fail(text, "date or time out of range");
  if (status >= 2)
    fail(text, "second " + std::to_string(t.second) + " is past the end of that day (no leap second then)");
  return t;
}

std::string formatUtc(const UtcTime& t) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02dT%02d:%02d:%06.3fZ", t.year, t.month, t.day, t.hour, t.minute,
                t.second);
  return buffer;
}

AstroTime makeAstroTime(const UtcTime& utc, std::optional<double> deltaTSeconds) {
  AstroTime time;
  time.utc = utc;
  if (eraDtf2d("UTC", utc.year, utc.month, utc.day, utc.hour, utc.minute, utc.second, &time.utcJulian.dayStart,
               &time.utcJulian.dayFraction) < 0)
    throw InputError("UTC time " + formatUtc(utc) + " is out of range");
  time.ut1 = time.utcJulian;

  if (deltaTSeconds) {
    if (!std::isfinite(*deltaTSeconds)) throw InputError("delta T (TT - UT1) must be a finite number of seconds");
    time.deltaT = *deltaTSeconds;
  } else if (utc.year < 1960) {
    time.deltaT = longTermDeltaT(utc.year + (utc.month - 0.5) / 12.0);
  } else {
    double taiMinusUtc = 0.0;
    double fractionOfDay = (utc.hour * 3600.0 + utc.minute * 60.0 + utc.second) / kSecondsPerDay;
    // Status 1 ("dubious year": past the table's end) still returns the latest TAI - UTC: keep it.
    if (eraDat(utc.year, utc.month, utc.day, std::fmin(fractionOfDay, 1.0), &taiMinusUtc) < 0)
      throw InputError("UTC time " + formatUtc(utc) + " is out of range for the leap-second table");
    time.deltaT = taiMinusUtc + kTTMinusTAI;
  }
  time.tt = {time.ut1.dayStart, time.ut1.dayFraction + time.deltaT / kSecondsPerDay};
  return time;
}

AstroTime makeAstroTime(std::string_view iso8601, std::optional<double> deltaTSeconds) {
  return makeAstroTime(parseUtc(iso8601), deltaTSeconds);
}

namespace {
// Days since 1970-01-01 of a proleptic Gregorian date, and back (the civil-calendar algorithms in
// H. Hinnant, "chrono-Compatible Low-Level Date Algorithms": eras of 400 years, March-based years).
int64_t daysFromCivil(int64_t y, int m, int d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const int64_t yoe = y - era * 400;
  const int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

void civilFromDays(int64_t z, int& y, int& m, int& d) {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const int64_t doe = z - era * 146097;
  const int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const int64_t mp = (5 * doy + 2) / 153;
  d = int(doy - (153 * mp + 2) / 5 + 1);
  m = int(mp < 10 ? mp + 3 : mp - 9);
  y = int(yoe + era * 400 + (m <= 2));
}
}  // namespace

UtcTime addSeconds(const UtcTime& utc, double seconds) {
  double total = double(daysFromCivil(utc.year, utc.month, utc.day)) * 86400.0 + utc.hour * 3600.0 + utc.minute * 60.0 +
                 utc.second + seconds;
  double days = std::floor(total / 86400.0);
  double rest = total - days * 86400.0;
  UtcTime out;
  civilFromDays(int64_t(days), out.year, out.month, out.day);
  out.hour = int(rest / 3600.0);
  rest -= out.hour * 3600.0;
  out.minute = int(rest / 60.0);
  out.second = rest - out.minute * 60.0;
  return out;
}

}  // namespace firmament::astro
