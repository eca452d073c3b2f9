#pragma once
// `firmament bench weather` (docs/weather.md, "Error and cost per knob"): the weather simulation's two
// cost knobs, the grid (cells across the same 51.2 km square) and the model time step, each against a
// reference run on the finest grid with the shortest step. The simulation is chaotic (a one-ulp nudge
// moves a storm afternoon's cloud fraction by 0.015), so maps are not compared cell by cell: the error is
// the RMS over the day (06:00-20:00 local mean solar time, every 30 min) of the domain statistics a
// renderer sees (cloud fraction, mean cloud top, rain area, cumulonimbus fraction), and it is set beside
// a floor, the same statistics' RMS difference between the reference and the reference with other seeds
// (2 and 3; --quick: 2), the weather's own variability: a knob whose error is below it changes nothing
// a viewer could tell from another day of the same weather. Cost: this thread's CPU time per simulated day.
#include <filesystem>
#include <string>
#include <vector>

namespace firmament {

struct WeatherBenchConfig {
  std::filesystem::path outDir;
  bool quick = false;
  std::vector<std::string> presets;  // empty: fair-weather and thunderstorm (--quick: fair-weather)
  std::string environmentNote;
};

// One run's statistics against the reference's: RMS over the day's samples.
struct WeatherBenchErrors {
  double cloudFraction = 0.0;  // absolute (cover fraction)
  double meanTop_m = 0.0;
  double rainArea = 0.0;      // absolute (fraction of cells)
  double cumulonimbus = 0.0;  // absolute (fraction of cells)
};

struct WeatherBenchRow {
  std::string preset;
  int cells = 0;  // per side; the domain is the same square for every row
  double cellSize_m = 0.0;
  double timeStep_s = 0.0;
  bool reference = false;  // the reference's settings, run again (its errors are 0 if deterministic)
  bool isDefault = false;  // the scene defaults (256 cells of 200 m, 60 s)
  double cpuSecondsPerDay = 0.0;
  double meanCloudFraction = 0.0;  // over the day's samples
  WeatherBenchErrors error;
  WeatherBenchErrors floor;  // the reference against other seeds (same for every row of a preset)
};

// InputError for an unknown preset (before any work).
void checkWeatherBenchConfig(const WeatherBenchConfig& config);
std::vector<WeatherBenchRow> runWeatherBench(const WeatherBenchConfig& config);
// DIR/weather_results.csv and DIR/weather_report.md.
void writeWeatherBenchOutputs(const WeatherBenchConfig& config, const std::vector<WeatherBenchRow>& rows);

}  // namespace firmament
