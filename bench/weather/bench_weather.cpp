// bench_weather: median time of one 60 s step on 256² and 1024² grids (thunderstorm afternoon, so the
// convection and rain paths run), and the wall time of 24 simulated hours of fair weather at 60 s steps
// on a 256² grid. Single-threaded. Usage: bench_weather [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <numbers>
#include <vector>

#include "weather/weather_model.h"

using namespace firmament::weather;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// CPU time of this thread: on a shared machine it is what the step costs, whatever else runs.
double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

SunElevationFunction summerDay(const char* utc) {
  return analyticSunElevationFunction(46.55 * std::numbers::pi / 180.0, 7.98 * std::numbers::pi / 180.0, parseUtc(utc));
}

// Median step time (ms) after spinning the model up for `spinup_s` of model time.
double medianStepMs(int cells, const char* preset, double spinup_s, int repeats) {
  WeatherConfig c;
  c.preset = preset;
  c.cellsX = c.cellsY = cells;
  WeatherModel model(c, summerDay("2026-06-21T08:00:00Z"));
  model.advance(spinup_s);
  std::vector<double> times, cpu;
  for (int i = 0; i < repeats; ++i) {
    auto t0 = Clock::now();
    double c0 = threadCpuSeconds();
    model.step(60.0);
    cpu.push_back((threadCpuSeconds() - c0) * 1e3);
    times.push_back(seconds(t0, Clock::now()) * 1e3);
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu.begin(), cpu.end());
  auto stats = model.stats();
  std::printf("  %4d² %-14s step 60 s: median %.3f ms wall, %.3f ms CPU (min %.3f, max %.3f wall; %d sub-steps), "
              "cloud %.2f, max top %.0f m\n",
              cells, preset, times[times.size() / 2], cpu[cpu.size() / 2], times.front(), times.back(), model.lastSubsteps(),
              stats.cloudFraction, stats.maxTop_m);
  return times[times.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::printf("bench_weather (single thread)\n");
  medianStepMs(256, "fair-weather", quick ? 600 : 4 * 3600.0, quick ? 11 : 51);
  medianStepMs(256, "thunderstorm", quick ? 600 : 6 * 3600.0, quick ? 11 : 51);
  if (!quick) medianStepMs(1024, "thunderstorm", 3600.0, 11);

  WeatherConfig c;
  c.preset = "fair-weather";
  auto t0 = Clock::now();
  double c0 = threadCpuSeconds();
  WeatherModel model(c, summerDay("2026-06-21T03:00:00Z"));
  model.advance(quick ? 3600.0 : 24 * 3600.0);
  double wall = seconds(t0, Clock::now()), cpu = threadCpuSeconds() - c0;
  auto stats = model.stats();
  std::printf("  256² fair-weather %s at 60 s steps: %.2f s wall, %.2f s CPU (%.3f ms CPU/step), final cloud %.3f\n",
              quick ? "1 h" : "24 h", wall, cpu, cpu * 1e3 / (quick ? 60 : 1440), stats.cloudFraction);
  return 0;
}
