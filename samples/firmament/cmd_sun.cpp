// `firmament sun`: the Sun's topocentric zenith and azimuth for a place and a UTC time.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>

#include "astro/sun.h"
#include "core/error.h"
#include "samples/firmament/command.h"

namespace firmament::cli {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::string outsideRange(const std::string& name, double value, double lo, double hi, const char* meaning) {
  return "option --" + name + ": " + formatNumber("%g", value) + " is outside [" + formatNumber("%g", lo) + ", " +
         formatNumber("%g", hi) + "] (" + meaning + ")";
}

double requiredNumber(const Args& args, const std::string& name, const char* meaning, double lo, double hi) {
  if (!args.has(name)) throw InputError("firmament sun: missing --" + name + " (" + meaning + ")");
  double value = args.number(name, 0.0);
  if (value < lo || value > hi) throw InputError(outsideRange(name, value, lo, hi, meaning));
  return value;
}

double optionalNumber(const Args& args, const std::string& name, double fallback, double lo, double hi,
                      const char* meaning) {
  double value = args.number(name, fallback);
  if (!(value >= lo && value <= hi)) throw InputError(outsideRange(name, value, lo, hi, meaning));
  return value;
}

astro::RefractionModel refractionModel(const std::string& name) {
  if (name == "spa") return astro::RefractionModel::Spa;
  if (name == "erfa") return astro::RefractionModel::Erfa;
  if (name == "none") return astro::RefractionModel::None;
  throw InputError("option --refraction: '" + name + "' is not one of spa, erfa, none");
}

double roundTo6(double x) { return std::round(x * 1e6) / 1e6; }

int runSun(const Args& args) {
  double latitude = requiredNumber(args, "lat", "geodetic latitude in degrees, north positive", -90.0, 90.0);
  double longitude = requiredNumber(args, "lon", "longitude in degrees, east positive", -180.0, 180.0);
  auto utcText = args.get("utc");
  if (!utcText) throw InputError("firmament sun: missing --utc (e.g. --utc 2003-10-17T19:30:30Z)");
  double height = optionalNumber(args, "elevation", 0.0, -1000.0, 100000.0, "metres above the WGS84 ellipsoid");

  astro::ObservingConditions air;
  air.pressureHpa = optionalNumber(args, "pressure", air.pressureHpa, 0.0, 2000.0, "mbar");
  air.temperatureCelsius =
      optionalNumber(args, "temperature", air.temperatureCelsius, -100.0, 100.0, "degrees Celsius");
  std::string refractionName = args.getOr("refraction", "spa");
  air.refraction = refractionModel(refractionName);
  std::optional<double> deltaT;
  if (args.has("delta-t")) deltaT = optionalNumber(args, "delta-t", 0.0, -1e6, 1e6, "TT - UT1 in seconds");

  astro::AstroTime time = astro::makeAstroTime(*utcText, deltaT);
  astro::GeodeticLocation place = astro::GeodeticLocation::fromDegrees(latitude, longitude, height);
  astro::TopocentricPosition sun = astro::sunPosition(time, place, air);
  double zenithDeg = sun.zenith / kDegree, azimuthDeg = sun.azimuth / kDegree;

  if (args.has("json")) {
    glm::dvec3 d = sun.directionEnu();
    nlohmann::ordered_json out = {
        {"utc", astro::formatUtc(time.utc)},
        {"latitude_deg", latitude},
        {"longitude_deg", longitude},
        {"elevation_m", height},
        {"pressure_mbar", air.pressureHpa},
        {"temperature_c", air.temperatureCelsius},
        {"delta_t_s", time.deltaT},
        {"refraction", refractionName},
        {"zenith_deg", roundTo6(zenithDeg)},
        {"azimuth_deg", roundTo6(azimuthDeg)},
        {"elevation_deg", roundTo6(90.0 - zenithDeg)},
        {"geometric_zenith_deg", roundTo6(sun.geometricZenith / kDegree)},
        {"direction_enu", {d.x, d.y, d.z}},
        {"distance_au", sun.distance / 149597870.7e3},
    };
    std::printf("%s\n", out.dump(2).c_str());
  } else {
    std::printf("zenith_deg  %.6f\nazimuth_deg %.6f\n", zenithDeg, azimuthDeg);
  }
  return kExitOk;
}

const CommandRegistration registration{Command{
    "sun",
    "topocentric zenith and azimuth of the Sun for a place and UTC time (ERFA; azimuth clockwise from north)",
    "sun --lat DEG --lon DEG --utc TIME [--elevation M] [--pressure MBAR] [--temperature C] [--delta-t S]\n"
    "           [--refraction spa|erfa|none] [--json]",
    {
        {"lat", "DEG", "geodetic latitude (WGS84), north positive"},
        {"lon", "DEG", "longitude, east positive"},
        {"elevation", "M", "height above the WGS84 ellipsoid in metres (default 0)"},
        {"utc", "TIME", "ISO 8601 time, e.g. 2003-10-17T19:30:30Z or 2003-10-17T12:30:30-07:00"},
        {"pressure", "MBAR", "air pressure for refraction (default 1013.25)"},
        {"temperature", "C", "air temperature for refraction (default 15)"},
        {"delta-t", "S", "TT - UT1 in seconds (default: from the leap-second table)"},
        {"refraction", "MODEL", "spa (default, NREL SPA's Bennett form), erfa, or none"},
        {"json", "", "print a JSON object instead of two lines"},
    },
    0,
    0,
    runSun,
}};

}  // namespace
}  // namespace firmament::cli
