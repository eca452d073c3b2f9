// Preset schedules blend smoothly, an interrupting change makes no jump; the scene's weather section
// parses with clear errors; the schema documents every key the parser accepts.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tests/support/test_paths.h"
#include "tests/weather/weather_test_support.h"
#include "weather/preset_schedule.h"
#include "weather/sun_elevation.h"
#include "weather/weather_config.h"

using namespace firmament::weather;
using nlohmann::json;

namespace {

// Largest change of any parameter over one second, relative to the parameter's range among presets.
double maxJumpPerSecond(const PresetSchedule& schedule, double from_s, double to_s) {
  std::array<double, PresetParameters::kCount> lo, hi;
  lo.fill(1e300);
  hi.fill(-1e300);
  for (const auto& name : presetNames()) {
    auto v = presetParameters(name).toArray();
    for (int i = 0; i < PresetParameters::kCount; ++i) {
      lo[i] = std::min(lo[i], v[i]);
      hi[i] = std::max(hi[i], v[i]);
    }
  }
  double worst = 0.0;
  auto previous = schedule.parametersAt(from_s).toArray();
  for (double t = from_s + 1.0; t <= to_s; t += 1.0) {
    auto v = schedule.parametersAt(t).toArray();
    for (int i = 0; i < PresetParameters::kCount; ++i)
      if (hi[i] > lo[i]) worst = std::max(worst, std::fabs(v[i] - previous[i]) / (hi[i] - lo[i]));
    previous = v;
  }
  return worst;
}

}  // namespace

TEST(Schedule, TransitionsAreSmoothAndReachTheTarget) {
  PresetSchedule s("fair-weather", {{3600.0, "thunderstorm", 3600.0}});
  // A smoothstep over 3600 s changes by at most 1.5/3600 of the range per second.
  EXPECT_LT(maxJumpPerSecond(s, 0.0, 3 * 3600.0), 1.5 / 3600.0 + 1e-9);
  auto end = s.parametersAt(2 * 3600.0 + 1.0).toArray(), target = presetParameters("thunderstorm").toArray();
  for (int i = 0; i < PresetParameters::kCount; ++i) EXPECT_DOUBLE_EQ(end[i], target[i]);
}

TEST(Schedule, InterruptedTransitionHasNoJump) {
  // Overcast starts blending at 1 h; at 1.5 h, mid-way, a change to thunderstorm interrupts it.
  PresetSchedule s("clear", {{3600.0, "overcast", 3600.0}, {5400.0, "thunderstorm", 1800.0}});
  auto before = s.parametersAt(5400.0 - 1e-6).toArray(), after = s.parametersAt(5400.0).toArray();
  for (int i = 0; i < PresetParameters::kCount; ++i) EXPECT_NEAR(before[i], after[i], 1e-6 * (1 + std::fabs(after[i])));
  EXPECT_LT(maxJumpPerSecond(s, 0.0, 4 * 3600.0), 1.5 / 1800.0 + 1e-9);
  EXPECT_EQ(s.presetAt(6000.0), "thunderstorm");
}

TEST(Config, ParsesTheWeatherSection) {
  json w = json::parse(R"({"preset": "thunderstorm", "seed": 9, "wind": {"speed_m_s": 12, "from_deg": 200,
      "shear_m_s_per_km": 3, "turbulence_m_s": 0.5}, "grid": {"cells_x": 128, "cells_y": 64, "cell_size_m": 250},
      "time_step_s": 30, "heating_scale": 1.2, "surface_heterogeneity": 0.1,
      "schedule": [{"at_h": 6, "preset": "overcast", "transition_h": 2}]})");
  WeatherConfig c = configFromJson(w);
  EXPECT_EQ(c.preset, "thunderstorm");
  EXPECT_EQ(c.seed, 9u);
  EXPECT_EQ(c.cellsX, 128);
  EXPECT_EQ(c.cellsY, 64);
  EXPECT_DOUBLE_EQ(c.cellSize_m, 250.0);
  EXPECT_DOUBLE_EQ(c.windShear_m_s_per_km, 3.0);
  ASSERT_EQ(c.schedule.size(), 1u);
  EXPECT_DOUBLE_EQ(c.schedule[0].at_s, 6 * 3600.0);
  EXPECT_DOUBLE_EQ(c.schedule[0].transition_s, 2 * 3600.0);
}

TEST(Config, BadInputNamesThePath) {
  auto message = [](const char* text) {
    try {
      configFromJson(json::parse(text));
    } catch (const firmament::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"presett": "clear"})").find("/weather/presett"), std::string::npos);
  EXPECT_NE(message(R"({"preset": "hurricane"})").find("allowed"), std::string::npos);
  EXPECT_NE(message(R"({"wind": {"speed_m_s": 500}})").find("/weather/wind/speed_m_s"), std::string::npos);
  EXPECT_NE(message(R"({"grid": {"cells_x": 2.5}})").find("integer"), std::string::npos);
  EXPECT_NE(message(R"({"schedule": [{"preset": "clear"}]})").find("at_h"), std::string::npos);
}

TEST(Config, SchemaDocumentsEveryAcceptedKey) {
  std::ifstream in(firmament::test::sourceDir() / "core" / "scene_schema.json");
  json schema = json::parse(in);
  const json& w = schema.at("properties").at("weather");
  // Every property has type, default (objects and arrays aside, and fields whose absence has a documented
  // meaning: x-optional-section) and description; numbers have a range.
  std::function<void(const json&, const std::string&)> check = [&](const json& node, const std::string& path) {
    for (auto it = node.at("properties").begin(); it != node.at("properties").end(); ++it) {
      const json& p = it.value();
      std::string where = path + "/" + it.key();
      EXPECT_TRUE(p.contains("type")) << where;
      EXPECT_TRUE(p.contains("description")) << where;
      std::string type = p.value("type", "");
      if (type == "object") {
        check(p, where);
      } else if (type == "array") {
        check(p.at("items"), where);
      } else {
        EXPECT_TRUE(p.contains("default") || p.value("x-optional-section", false) ||
                    path.find("schedule") != std::string::npos)
            << where;
      }
      if (type == "number" || type == "integer") {
        EXPECT_TRUE(p.contains("minimum") && p.contains("maximum")) << where;
      }
    }
  };
  check(w, "/weather");
  // A section with every schema key set to its default parses (the parser knows each key).
  std::function<json(const json&)> defaults = [&](const json& node) {
    json out = json::object();
    for (auto it = node.at("properties").begin(); it != node.at("properties").end(); ++it) {
      const json& p = it.value();
      if (p.value("type", "") == "object")
        out[it.key()] = defaults(p);
      else if (p.contains("default"))
        out[it.key()] = p.at("default");
    }
    return out;
  };
  EXPECT_NO_THROW(configFromJson(defaults(w)));
}

TEST(Config, PresetScenesParse) {
  for (const char* name : {"fair-weather", "thunderstorm", "clear", "scattered-showers", "overcast", "frontal"}) {
    std::ifstream in(firmament::test::sourceDir() / "scenes" / (std::string(name) + ".json"));
    ASSERT_TRUE(in.good()) << name;
    json scene = json::parse(in);
    ASSERT_TRUE(scene.contains("weather")) << name;
    ASSERT_TRUE(scene.contains("clouds")) << name;
    EXPECT_NO_THROW(configFromJson(scene.at("weather"))) << name;
    EXPECT_NO_THROW(firmament::astro::parseUtc(scene.at("time").at("utc").get<std::string>())) << name;
  }
}

TEST(SunElevation, TheModelsSunIsTheEphemerisSun) {
  // 46.55° N on 21 June: noon elevation 90° − 46.55° + 23.44° = 66.89° (the equation of time moves noon by
  // under 2 min that day); local mean noon at 12:00 − 7.98°/15 UTC, 9 h after the summer day's start.
  const SunElevationFunction sun = firmament::weather::test::summerDay();
  const double noon_s = (12.0 - 7.98 / 15.0 - 3.0) * 3600.0;
  EXPECT_NEAR(sun(noon_s) * 180.0 / std::numbers::pi, 66.89, 0.1);
  EXPECT_LT(sun(noon_s + 12 * 3600.0), 0.0);
  EXPECT_LT(sun(0.0), 0.0);  // 03:00 UTC: before sunrise
  EXPECT_DOUBLE_EQ(constantSunElevation(0.25)(12345.0), 0.25);
}
