// firmament weather SCENE --hours H --out DIR: runs the weather simulation alone and writes the weather
// maps (EXR), colour-coded previews (PNG), stats.csv and a plot of it (stats.svg).
//
// TODO(main): scene loading here is a minimal stand-in (JSON parse + --set by JSON pointer + the weather
// section's own validation). Swap in Scene::load(path, overrides) when core/scene.h lands; the sun will
// come from astro's ephemeris instead of weather/solar_day.h's analytic day.
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
#include "weather/solar_day.h"
#include "weather/svg_plot.h"
#include "weather/weather_config.h"
#include "weather/weather_model.h"
#include "weather/weather_preview.h"

#if __has_include("core/exr_io.h")
#include "core/exr_io.h"
#define FIRMAMENT_HAVE_EXR_IO 1
#else
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#endif
#if __has_include("core/png_io.h")
#include "core/png_io.h"
#define FIRMAMENT_HAVE_PNG_IO 1
#else
#include <png.h>
#endif

namespace firmament::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Write to a temporary name beside the target, then rename: a crash never leaves a half-written file.
template <typename WriteFn>
void writeAtomically(const fs::path& target, WriteFn write) {
  fs::path temporary = target;
  temporary += ".tmp";
  write(temporary);
  std::error_code ec;
  fs::rename(temporary, target, ec);
  if (ec) throw RuntimeError("cannot rename " + temporary.string() + " to " + target.string() + ": " + ec.message());
}

void writeText(const fs::path& path, const std::string& text) {
  writeAtomically(path, [&](const fs::path& p) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    if (!out) throw RuntimeError("cannot write " + p.string());
  });
}

void writeMapExr(const fs::path& path, const Image& image) {
#ifdef FIRMAMENT_HAVE_EXR_IO
  writeAtomically(path, [&](const fs::path& p) { writeExr(p, image); });
#else
  // Stand-in until core/exr_io.h (branch images) is merged: 32-bit float RGBA, metadata as strings.
  writeAtomically(path, [&](const fs::path& p) {
    Imf::Header header(image.width, image.height);
    const char* names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < image.channels; ++c) header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    for (const auto& [key, value] : image.metadata) header.insert(key, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    size_t pixelStride = sizeof(float) * image.channels;
    for (int c = 0; c < image.channels; ++c)
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)(image.pixels.data() + c), pixelStride,
                                        pixelStride * image.width));
    Imf::OutputFile file(p.string().c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  });
#endif
}

void writeRgbPng(const fs::path& path, int width, int height, const std::vector<uint8_t>& rgb) {
#ifdef FIRMAMENT_HAVE_PNG_IO
  writeAtomically(path, [&](const fs::path& p) { writePng(p, width, height, 3, rgb.data()); });
#else
  // Stand-in until core/png_io.h (branch images) is merged.
  writeAtomically(path, [&](const fs::path& p) {
    FILE* f = std::fopen(p.string().c_str(), "wb");
    if (!f) throw RuntimeError("cannot write " + p.string());
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      std::fclose(f);
      throw RuntimeError("PNG encoding failed for " + p.string());
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y) png_write_row(png, rgb.data() + size_t(y) * width * 3);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
  });
#endif
}

// Minimal scene reading: the JSON file and --set /pointer=value overrides (value parsed as JSON, else
// taken as a string).
json loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the scene file");
  json scene;
  try {
    scene = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path + ": not valid JSON: " + e.what());
  }
  for (const auto& o : overrides) {
    auto eq = o.find('=');
    if (eq == std::string::npos || o.empty() || o[0] != '/')
      throw InputError("--set '" + o + "': expected /json/pointer=value");
    std::string pointer = o.substr(0, eq), text = o.substr(eq + 1);
    json value;
    try {
      value = json::parse(text);
    } catch (const json::exception&) {
      value = text;
    }
    try {
      scene[json::json_pointer(pointer)] = value;
    } catch (const json::exception& e) {
      throw InputError("--set '" + o + "': " + e.what());
    }
  }
  return scene;
}

double sceneNumber(const json& scene, const char* section, const char* key, double fallback, double lo, double hi) {
  if (!scene.contains(section) || !scene[section].contains(key)) return fallback;
  const json& v = scene[section][key];
  if (!v.is_number() || v.get<double>() < lo || v.get<double>() > hi)
    throw InputError(std::string("/") + section + "/" + key + ": expected a number in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  return v.get<double>();
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

  json scene = loadScene(scenePath, args.all("set"));
  if (!scene.contains("weather"))
    throw InputError(scenePath + ": the scene has no \"weather\" section (nothing to simulate)");
  WeatherConfig config = configFromJson(scene["weather"]);
  double latitude = sceneNumber(scene, "location", "latitude_deg", 46.55, -90, 90) * std::numbers::pi / 180.0;
  double longitude = sceneNumber(scene, "location", "longitude_deg", 7.98, -180, 180) * std::numbers::pi / 180.0;
  config.surfacePressure_Pa = surfacePressureFromHeight(sceneNumber(scene, "location", "height_m", 1200, -500, 9000));
  std::string utc = "2026-06-21T15:30:00Z";
  if (scene.contains("time") && scene["time"].contains("utc")) {
    if (!scene["time"]["utc"].is_string()) throw InputError("/time/utc: expected a string");
    utc = scene["time"]["utc"].get<std::string>();
  }
  UtcTime start = parseUtc(utc);

  fs::path dir(*out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RuntimeError("cannot create " + dir.string() + ": " + ec.message());

  WeatherModel model(config, analyticSunElevationFunction(latitude, longitude, start));
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
          " cells of " + std::to_string(int(config.cellSize_m)) + " m, " + std::to_string(hours) + " h from " + utc);
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
  plot.xLabel = "time since start (h)";
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
          "; water imbalance " + std::to_string(std::fabs(b.imbalance_kg()) / std::max(b.initial_kg, 1.0)) + " relative");
  return kExitOk;
}

const CommandRegistration registration(Command{
    "weather",
    "run the weather simulation alone: weather maps (EXR), previews (PNG), stats.csv and stats.svg",
    "weather SCENE --out DIR [--hours H] [--interval-min M] [--set /PATH=VALUE ...]",
    {{"out", "DIR", "output folder (created if missing)", false, 'o'},
     {"hours", "H", "simulated hours (default 24)"},
     {"interval-min", "M", "minutes between written maps (default 30)"},
     setOption()},
    1,
    1,
    runWeather});

}  // namespace
}  // namespace firmament::cli
