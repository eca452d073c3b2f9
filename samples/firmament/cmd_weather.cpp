// firmament weather SCENE --hours H --out DIR: runs the weather simulation alone and writes the weather
// maps (EXR), colour-coded previews (PNG), stats.csv and a plot of it (stats.svg).
//
// The simulation starts where the render's does (sky/scene_weather.h, sceneWeatherStart: weather.start_utc,
// or the local mean solar midnight before the scene's time), so the maps at a time are the ones the
// render's clouds read at that time. The sun follows astro's ephemeris for the scene's place (refraction
// included).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/log.h"
#include "samples/firmament/command.h"
#include "weather/svg_plot.h"
#include "weather/weather_config.h"
#include "weather/weather_model.h"
#include "weather/weather_preview.h"

#include "astro/geodetic.h"
#include "astro/sun.h"
#include "astro/time.h"
#include "core/atomic_file.h"
#include "core/exr_io.h"
#include "core/png_io.h"
#include "core/scene.h"
#include "sky/scene_weather.h"

namespace firmament::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void writeText(const fs::path& path, const std::string& text) { writeTextFileAtomically(path, text); }

void writeMapExr(const fs::path& path, const Image& image) { writeExr(path, image); }

void writeRgbPng(const fs::path& path, int width, int height, const std::vector<uint8_t>& rgb) {
  writePng(path, width, height, 3, rgb.data());
}

int runWeather(const Args& args) {
  using namespace firmament::weather;
  const std::string scenePath = args.positionals.at(0);
  const double hours = args.number("hours", 24.0);
  const double intervalMin = args.number("interval-min", 30.0);
  if (!(hours > 0.0 && hours <= 8760.0)) throw InputError("--hours must be in (0, 8760]");
  if (!(intervalMin >= 1.0 && intervalMin <= 1440.0)) throw InputError("--interval-min must be in [1, 1440]");
  auto out = args.get("out");
  if (!out) throw InputError("firmament weather: --out DIR is required");

  Scene scene = Scene::load(scenePath, args.all("set"));
  if (!scene.hasSection("weather"))
    throw InputError(scenePath + ": the scene has no \"weather\" section (nothing to simulate)");
  WeatherConfig config = configFromJson(scene.at("/weather"));
  auto location =
      astro::GeodeticLocation::fromDegrees(scene.number("/location/latitude_deg"),
                                           scene.number("/location/longitude_deg"), scene.number("/location/height_m"));
  double latitude = location.latitude, longitude = location.longitude;
  config.surfacePressure_Pa = surfacePressureFromHeight(scene.number("/location/height_m"));
  const astro::UtcTime start = sceneWeatherStart(scene);
  const std::string utc = astro::formatUtc(start);
  const double sceneAt_h = sceneWeatherRunSeconds(scene) / 3600.0;

  fs::path dir(*out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RuntimeError("cannot create " + dir.string() + ": " + ec.message());

  WeatherModel model(config, astro::sunElevationAfter(location, start));
  RegionPlacement placement{latitude, longitude, 6360000.0};
  const double duration = hours * 3600.0, interval = intervalMin * 60.0;
  const double statsInterval = std::min(interval, std::max(600.0, config.timeStep_s));
  std::string csv = std::string(statsCsvHeader()) + "\n";
  std::vector<WeatherStats> series;
  auto record = [&] {
    WeatherStats s = model.stats();
    series.push_back(s);
    csv += statsCsvRow(s) + "\n";
  };
  int frame = 0;
  auto writeFrame = [&] {
    WeatherMap map = model.map(placement);
    map.map.metadata["weather:start_utc"] = utc;
    map.wind.metadata["weather:start_utc"] = utc;
    char name[64];
    std::snprintf(name, sizeof name, "weather_%04d.exr", frame);
    writeMapExr(dir / name, map.map);
    std::snprintf(name, sizeof name, "wind_%04d.exr", frame);
    writeMapExr(dir / name, map.wind);
    std::snprintf(name, sizeof name, "preview_%04d.png", frame);
    writeRgbPng(dir / name, map.map.width, map.map.height, previewRgb(map));
    ++frame;
  };

  logInfo("weather: " + config.preset + ", " + std::to_string(config.cellsX) + "x" + std::to_string(config.cellsY) +
          " cells of " + std::to_string(int(config.cellSize_m)) + " m, " + std::to_string(hours) + " h from " + utc +
          " (the scene's time " + scene.string("/time/utc") + " is at " + std::to_string(sceneAt_h) + " h)");
  record();
  writeFrame();
  Progress progress("weather", uint64_t(std::ceil(duration / statsInterval)));
  double nextFrame = interval;
  while (model.time_s() < duration - 1e-6) {
    double target = std::min(duration, model.time_s() + statsInterval);
    model.advance(target - model.time_s());
    record();
    if (model.time_s() >= nextFrame - 1e-6) {
      writeFrame();
      nextFrame += interval;
    }
    progress.advance();
  }
  writeText(dir / "stats.csv", csv);

  LinePlot plot;
  plot.title = "Weather: " + config.preset + " from " + utc;
  plot.xLabel = "time since start (h); the scene's time at " + std::to_string(sceneAt_h).substr(0, 5) + " h";
  plot.leftLabel = "fraction of the domain";
  plot.rightLabel = "cloud top (m)";
  PlotSeries cloud{"cloud fraction", "#1f77b4", {}, false}, rain{"precipitation area", "#2ca02c", {}, false},
      meanTop{"mean top", "#ff7f0e", {}, true}, maxTop{"max top", "#d62728", {}, true};
  for (const auto& s : series) {
    plot.x.push_back(s.time_h);
    cloud.values.push_back(s.cloudFraction);
    rain.values.push_back(s.precipAreaFraction);
    meanTop.values.push_back(s.meanTop_m);
    maxTop.values.push_back(s.maxTop_m);
  }
  plot.series = {cloud, rain, meanTop, maxTop};
  writeText(dir / "stats.svg", renderSvg(plot));
  WaterBudget b = model.waterBudget();
  logInfo("weather: wrote " + std::to_string(frame) + " maps, stats.csv and stats.svg to " + dir.string() +
          "; water imbalance " + std::to_string(std::fabs(b.imbalance_kg()) / std::max(b.initial_kg, 1.0)) +
          " relative");
  return kExitOk;
}

const CommandRegistration registration(Command{
    "weather",
    "run the weather simulation alone: weather maps (EXR), previews (PNG), stats.csv and stats.svg",
    "weather SCENE --out DIR [--hours H] [--interval-min M] [--set /PATH=VALUE ...]",
    {{"out", "DIR", "output folder (created if missing)", false, 'o'},
     {"hours", "H", "simulated hours from the start (default 24: the scene's day)"},
     {"interval-min", "M", "minutes between written maps (default 30)"},
     setOption()},
    1,
    1,
    runWeather});

}  // namespace
}  // namespace firmament::cli
