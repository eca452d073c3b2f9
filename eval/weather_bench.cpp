// `firmament bench weather`: the weather grid and time step against a fine reference (weather_bench.h).
#include "eval/weather_bench.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "astro/geodetic.h"
#include "astro/sun.h"
#include "astro/time.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "weather/weather_model.h"
#include "weather/weather_presets.h"

namespace firmament {
namespace {

// The default scene's place and day: 46.55° N, 7.98° E, from the local mean solar midnight before
// 21 June 2026 (7.98° / 15° h = 31.92 min east of Greenwich: 23:28:04.8 UTC on 20 June), as a scene's
// simulation starts (sky/scene_weather.h).
constexpr double kLatitude_deg = 46.55, kLongitude_deg = 7.98;
constexpr const char* kStartUtc = "2026-06-20T23:28:04.800Z";
constexpr double kDomain_m = 51200.0;  // the scene default: 256 cells of 200 m
// The day's samples: every 30 min from 06:00 to 20:00 local mean solar time (29 samples), the hours
// with convective cloud; the night's near-empty statistics would only dilute the RMS.
constexpr double kFirstSample_s = 6.0 * 3600.0, kLastSample_s = 20.0 * 3600.0, kSampleEvery_s = 1800.0;

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Run {
  std::vector<weather::WeatherStats> samples;
  double cpuSecondsPerDay = 0.0;
};

struct Setting {
  int cells = 256;
  double timeStep_s = 60.0;
  uint32_t seed = 1;
};

Run simulate(const std::string& preset, const Setting& s) {
  weather::WeatherConfig c;
  c.preset = preset;
  c.seed = s.seed;
  c.cellsX = c.cellsY = s.cells;
  c.cellSize_m = kDomain_m / s.cells;
  c.timeStep_s = s.timeStep_s;
  const auto location = astro::GeodeticLocation::fromDegrees(kLatitude_deg, kLongitude_deg, 0.0);
  const double c0 = threadCpuSeconds();
  weather::WeatherModel model(c, astro::sunElevationAfter(location, astro::parseUtc(kStartUtc)));
  Run run;
  for (double t = kFirstSample_s; t <= kLastSample_s + 1.0; t += kSampleEvery_s) {
    model.advance(t - model.time_s());
    run.samples.push_back(model.stats());
  }
  run.cpuSecondsPerDay = (threadCpuSeconds() - c0) * 86400.0 / model.time_s();
  return run;
}

WeatherBenchErrors rmsDifference(const Run& a, const Run& b) {
  WeatherBenchErrors e;
  const size_t n = a.samples.size();
  for (size_t i = 0; i < n; ++i) {
    const weather::WeatherStats &x = a.samples[i], &y = b.samples[i];
    e.cloudFraction += std::pow(x.cloudFraction - y.cloudFraction, 2);
    e.meanTop_m += std::pow(x.meanTop_m - y.meanTop_m, 2);
    e.rainArea += std::pow(x.precipAreaFraction - y.precipAreaFraction, 2);
    e.cumulonimbus += std::pow(x.cumulonimbusFraction - y.cumulonimbusFraction, 2);
  }
  for (double* v : {&e.cloudFraction, &e.meanTop_m, &e.rainArea, &e.cumulonimbus}) *v = std::sqrt(*v / double(n));
  return e;
}

double meanCloudFraction(const Run& r) {
  double sum = 0.0;
  for (const auto& s : r.samples) sum += s.cloudFraction;
  return sum / double(r.samples.size());
}

std::string number(double v, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

}  // namespace

void checkWeatherBenchConfig(const WeatherBenchConfig& config) {
  for (const std::string& p : config.presets)
    if (!weather::isPresetName(p)) {
      std::string list;
      for (const auto& n : weather::presetNames()) list += (list.empty() ? "" : ", ") + n;
      throw InputError("firmament bench weather: unknown preset '" + p + "' (" + list + ")");
    }
}

std::vector<WeatherBenchRow> runWeatherBench(const WeatherBenchConfig& config) {
  checkWeatherBenchConfig(config);
  std::vector<std::string> presets = config.presets;
  if (presets.empty())
    presets = config.quick ? std::vector<std::string>{"fair-weather"}
                           : std::vector<std::string>{"fair-weather", "thunderstorm"};
  // Reference: the finest grid with the shortest step. Quick: a coarser reference, one floor seed, the
  // reference run again and a coarser grid at two steps (a test's seconds under the sanitizers).
  const Setting reference = config.quick ? Setting{128, 60.0} : Setting{512, 30.0};
  const std::vector<int> cells = config.quick ? std::vector<int>{64, 128} : std::vector<int>{128, 256, 512};
  const std::vector<double> steps =
      config.quick ? std::vector<double>{60.0, 300.0} : std::vector<double>{30.0, 60.0, 120.0, 300.0, 900.0};
  const std::vector<uint32_t> floorSeeds = config.quick ? std::vector<uint32_t>{2} : std::vector<uint32_t>{2, 3};

  std::vector<WeatherBenchRow> rows;
  for (const std::string& preset : presets) {
    logInfo("bench weather: " + preset + ", reference " + std::to_string(reference.cells) + " cells, " +
            number(reference.timeStep_s, "%.0f") + " s steps");
    const Run ref = simulate(preset, reference);
    WeatherBenchErrors floor;
    for (uint32_t seed : floorSeeds) {
      Setting other = reference;
      other.seed = seed;
      const WeatherBenchErrors e = rmsDifference(simulate(preset, other), ref);
      floor.cloudFraction += e.cloudFraction * e.cloudFraction / double(floorSeeds.size());
      floor.meanTop_m += e.meanTop_m * e.meanTop_m / double(floorSeeds.size());
      floor.rainArea += e.rainArea * e.rainArea / double(floorSeeds.size());
      floor.cumulonimbus += e.cumulonimbus * e.cumulonimbus / double(floorSeeds.size());
    }
    for (double* v : {&floor.cloudFraction, &floor.meanTop_m, &floor.rainArea, &floor.cumulonimbus}) *v = std::sqrt(*v);
    for (int n : cells)
      for (double dt : steps) {
        if (config.quick && n == reference.cells && dt != reference.timeStep_s) continue;
        const Run run = simulate(preset, Setting{n, dt});
        WeatherBenchRow row;
        row.preset = preset;
        row.cells = n;
        row.cellSize_m = kDomain_m / n;
        row.timeStep_s = dt;
        row.reference = n == reference.cells && dt == reference.timeStep_s;
        row.isDefault = n == 256 && dt == 60.0;
        row.cpuSecondsPerDay = run.cpuSecondsPerDay;
        row.meanCloudFraction = meanCloudFraction(run);
        row.error = rmsDifference(run, ref);
        row.floor = floor;
        rows.push_back(row);
        logInfo("bench weather: " + preset + " " + std::to_string(n) + " cells, " + number(dt, "%.0f") +
                " s: " + number(row.cpuSecondsPerDay, "%.2f") + " s CPU per day, cloud fraction error " +
                number(row.error.cloudFraction, "%.4f") + " (floor " + number(floor.cloudFraction, "%.4f") + ")");
      }
  }
  return rows;
}

void writeWeatherBenchOutputs(const WeatherBenchConfig& config, const std::vector<WeatherBenchRow>& rows) {
  std::ostringstream csv;
  csv << "preset,cells,cell_size_m,time_step_s,reference,default,cpu_s_per_day,mean_cloud_fraction,"
         "cloud_fraction_rmse,mean_top_rmse_m,rain_area_rmse,cumulonimbus_rmse,floor_cloud_fraction,"
         "floor_mean_top_m,floor_rain_area,floor_cumulonimbus\n";
  for (const WeatherBenchRow& r : rows)
    csv << r.preset << ',' << r.cells << ',' << number(r.cellSize_m, "%.1f") << ',' << number(r.timeStep_s, "%.0f")
        << ',' << (r.reference ? 1 : 0) << ',' << (r.isDefault ? 1 : 0) << ',' << number(r.cpuSecondsPerDay, "%.4f")
        << ',' << number(r.meanCloudFraction, "%.5f") << ',' << number(r.error.cloudFraction, "%.6f") << ','
        << number(r.error.meanTop_m, "%.2f") << ',' << number(r.error.rainArea, "%.6f") << ','
        << number(r.error.cumulonimbus, "%.6f") << ',' << number(r.floor.cloudFraction, "%.6f") << ','
        << number(r.floor.meanTop_m, "%.2f") << ',' << number(r.floor.rainArea, "%.6f") << ','
        << number(r.floor.cumulonimbus, "%.6f") << '\n';
  writeTextFileAtomically(config.outDir / "weather_results.csv", csv.str());

  std::ostringstream md;
  md << "# bench weather\n\nRMS over 06:00-20:00 local mean solar time (every 30 min) of each run's domain "
        "statistics against the reference's; the floor is the reference against seeds 2 and 3. CPU: this "
        "thread's time per simulated day.";
  if (!config.environmentNote.empty()) md << ' ' << config.environmentNote;
  md << "\n";
  std::string preset;
  for (const WeatherBenchRow& r : rows) {
    if (r.preset != preset) {
      preset = r.preset;
      md << "\n## " << preset
         << "\n\n| cells | cell | step | CPU per day | cloud fraction | error: cloud fraction | "
            "mean top | rain area | Cb |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
         << "| floor (other seeds) | | | | | " << number(r.floor.cloudFraction, "%.4f") << " | "
         << number(r.floor.meanTop_m, "%.0f") << " m | " << number(r.floor.rainArea, "%.4f") << " | "
         << number(r.floor.cumulonimbus, "%.4f") << " |\n";
    }
    md << "| " << r.cells << (r.isDefault ? " (default)" : "") << (r.reference ? " (reference)" : "") << " | "
       << number(r.cellSize_m, "%.0f") << " m | " << number(r.timeStep_s, "%.0f") << " s | "
       << number(r.cpuSecondsPerDay, "%.2f") << " s | " << number(r.meanCloudFraction, "%.3f") << " | "
       << number(r.error.cloudFraction, "%.4f") << " | " << number(r.error.meanTop_m, "%.0f") << " m | "
       << number(r.error.rainArea, "%.4f") << " | " << number(r.error.cumulonimbus, "%.4f") << " |\n";
  }
  writeTextFileAtomically(config.outDir / "weather_report.md", md.str());
}

}  // namespace firmament
