// bench_weather: single-threaded CPU time of the weather model (docs/weather.md, "Benchmark").
//   - one 60 s step on 256² in three typical states: quiet (fair weather before sunrise), cloudy noon
//     (fair-weather cumulus at their peak) and a thunderstorm afternoon (storms raining);
//   - one 60 s step on 1024² (thunderstorm afternoon; report only);
//   - 24 simulated hours at 60 s steps on 256², fair weather and thunderstorm.
// Step times are the median of repeats (thread CPU time, which is what a step costs whatever else runs
// on a shared machine; wall time alongside). Usage:
//   bench_weather [--quick]                 the table above (--quick: fewer repeats, 1 h instead of 24 h)
//   bench_weather --series PRESET CELLS H   domain statistics every 30 min (tuning aid)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <numbers>
#include <vector>

#include "astro/sun.h"
#include "core/statistics.h"
#include "weather/weather_model.h"

using firmament::median;
using namespace firmament::weather;
namespace astro = firmament::astro;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// 21 June at 46.55° N, 7.98° E (the default scene), from 03:00 UTC (03:32 local mean solar time).
SunElevationFunction summerDay() {
  return astro::sunElevationAfter(astro::GeodeticLocation::fromDegrees(46.55, 7.98, 0.0),
                                  astro::parseUtc("2026-06-21T03:00:00Z"));
}
double localSolarHours(double t_s) { return 3.0 + 7.98 / 15.0 + t_s / 3600.0; }

// The state a case measures: from `earliest_s`, advanced in 10 min chunks until `ready` holds (at most
// 12 h more), so the case stays "cloudy" or "stormy" whatever the physics' timing.
template <class Ready>
void stepCase(const char* label, int cells, const char* preset, double earliest_s, int repeats, Ready ready) {
  WeatherConfig c;
  c.preset = preset;
  c.cellsX = c.cellsY = cells;
  WeatherModel model(c, summerDay());
  model.advance(earliest_s);
  for (int k = 0; k < 72 && !ready(model.stats()); ++k) model.advance(600.0);
  const double spinup_s = model.time_s();
  model.enableOperatorTimes(true);
  std::vector<double> wall, cpu;
  WeatherStats before = model.stats();
  for (int i = 0; i < repeats; ++i) {
    auto t0 = Clock::now();
    double c0 = threadCpuSeconds();
    model.step(60.0);
    cpu.push_back((threadCpuSeconds() - c0) * 1e3);
    wall.push_back(seconds(t0, Clock::now()) * 1e3);
  }
  std::printf(
      "  %-24s %4d² %-13s %5.2f h: median %7.3f ms CPU, %7.3f ms wall (%d steps, %d sub-steps in the last; cloud %.2f, "
      "Cb %.3f, rain area %.3f)\n",
      label, cells, preset, localSolarHours(spinup_s), median(cpu), median(wall), repeats, model.lastSubsteps(),
      before.cloudFraction, before.cumulonimbusFraction, before.precipAreaFraction);
  std::printf("      per step:");
  const OperatorTimes& t = model.operatorTimes();
  for (int k = 0; k < OperatorTimes::kCount; ++k)
    std::printf(" %s %.3f", OperatorTimes::kNames[k], t.seconds[k] * 1e3 / repeats);
  std::printf(" (ms CPU)\n");
}

void dayCase(const char* preset, double hours) {
  WeatherConfig c;
  c.preset = preset;
  auto t0 = Clock::now();
  double c0 = threadCpuSeconds();
  WeatherModel model(c, summerDay());
  model.advance(hours * 3600.0);
  double wall = seconds(t0, Clock::now()), cpu = threadCpuSeconds() - c0;
  std::printf("  256² %-13s %4.0f h at 60 s steps: %6.2f s CPU, %6.2f s wall (%.3f ms CPU per step)\n", preset, hours,
              cpu, wall, cpu * 1e3 / (hours * 60.0));
}

void series(const char* preset, int cells, double hours) {
  WeatherConfig c;
  c.preset = preset;
  c.cellsX = c.cellsY = cells;
  WeatherModel model(c, summerDay());
  std::printf(
      "# %s %d² from 03:32 local solar time\n"
      "# local_h cloud mean_top max_top rain_area cb_fraction layer_depth_m subsidence_K mass_flux_m_s min_T_K "
      "mean_T_K\n",
      preset, cells);
  for (int k = 0; k <= int(hours * 2); ++k) {
    if (k > 0) model.advance(1800.0);
    WeatherStats s = model.stats();
    const auto& T = model.state().temperature;
    double mean = 0.0;
    for (float t : T) mean += t;
    std::printf("%6.2f %.3f %6.0f %6.0f %.3f %.3f %5.0f %5.2f %.4f %6.2f %5.2f\n", localSolarHours(model.time_s()),
                s.cloudFraction, s.meanTop_m, s.maxTop_m, s.precipAreaFraction, s.cumulonimbusFraction,
                model.layerDepth_m(), model.subsidenceWarming_K(), model.state().meanMassFlux_m_s,
                double(*std::min_element(T.begin(), T.end())), mean / double(T.size()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 5 && std::strcmp(argv[1], "--series") == 0) {
    series(argv[2], std::atoi(argv[3]), std::atof(argv[4]));
    return 0;
  }
  bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int repeats = quick ? 11 : 31;
  std::printf("bench_weather (single thread; CPU time of this thread)\n");
  auto any = [](const WeatherStats&) { return true; };
  auto cloudy = [](const WeatherStats& s) { return s.cloudFraction >= 0.15; };
  auto stormy = [](const WeatherStats& s) { return s.cumulonimbusFraction >= 0.01 && s.precipAreaFraction >= 0.01; };
  stepCase("quiet (before sunrise)", 256, "fair-weather", 0.5 * 3600.0, repeats, any);
  stepCase("cloudy noon", 256, "fair-weather", 8.0 * 3600.0, repeats, cloudy);
  stepCase("thunderstorm afternoon", 256, "thunderstorm", 8.0 * 3600.0, repeats, stormy);
  if (!quick) stepCase("thunderstorm afternoon", 1024, "thunderstorm", 8.0 * 3600.0, 5, stormy);
  for (const char* preset : {"fair-weather", "thunderstorm"}) dayCase(preset, quick ? 1.0 : 24.0);
  return 0;
}
