#include "weather/weather_model.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <numbers>

#include "core/error.h"
#include "weather/boundary_layer_growth.h"
#include "weather/compensating_subsidence.h"
#include "weather/convection.h"
#include "weather/fast_math_sse.h"
#include "weather/microphysics.h"
#include "weather/physical_constants.h"
#include "weather/sounding.h"
#include "weather/stratiform.h"
#include "weather/surface_heating.h"
#include "weather/thermodynamics.h"
#include "weather/value_noise.h"

namespace firmament::weather {
namespace {

// Charges the CPU time of this thread since the previous mark to one operator (only when timing is on;
// CPU time, not wall clock, so that other processes on a shared machine do not count).
class OperatorClock {
 public:
  OperatorClock(OperatorTimes& times, bool on) : times_(times), on_(on) {
    if (on_) last_ = now();
  }
  void charge(int op) {
    if (!on_) return;
    double t = now();
    times_.seconds[op] += t - last_;
    last_ = t;
  }

 private:
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
  OperatorTimes& times_;
  bool on_;
  double last_ = 0.0;
};

}  // namespace

WeatherModel::WeatherModel(const WeatherConfig& config, SunElevationFunction sunElevation)
    : config_(config),
      sunElevation_(std::move(sunElevation)),
      schedule_(config.preset, config.schedule),
      state_(config.cellsX, config.cellsY, config.cellSize_m),
      wind_(config.cellsX, config.cellsY, config.cellSize_m, config.seed),
      subsidence_(config.cellsX, config.cellsY, config.cellSize_m) {
  if (config.cellsX < 4 || config.cellsY < 4 || !(config.cellSize_m > 0.0))
    throw InputError("weather grid must be at least 4 × 4 cells with a positive cell size");
  if (!sunElevation_) throw InputError("weather model needs a sun-elevation function");
  // Surface heterogeneity: smooth seeded noise with ~3 km features, mean 1, never negative.
  const double featureCells = std::max(2.0, 3000.0 / config.cellSize_m);
  Field noise = periodicNoiseField(config.cellsX, config.cellsY, featureCells, 3, hashCombine(config.seed, 11));
  heatingMap_.resize(noise.size());
  for (size_t c = 0; c < noise.size(); ++c)
    heatingMap_[c] = std::max(0.0f, 1.0f + float(config.surfaceHeterogeneity) * noise[c]);
  // Initial state: the background vapour, a faint seeded temperature texture, no cloud; the layer at its
  // morning depth.
  PresetParameters p = schedule_.parametersAt(0.0);
  state_.layerDepth_m = p.boundaryLayerDepth_m;
  subsidenceWarming_.assign(state_.cells(), 0.0f);
  Field thermal = periodicNoiseField(config.cellsX, config.cellsY, featureCells / 2, 2, hashCombine(config.seed, 12));
  float vapour = float(backgroundVapour_kg_m2(p));
  for (size_t c = 0; c < state_.cells(); ++c) {
    state_.temperature[c] = 0.2f * thermal[c];
    state_.vapour[c] = vapour;
  }
  updateWind(p);
  initialWater_kg_ = state_.waterTotal_kg();
}

void WeatherModel::setHeatingMap(const std::vector<float>& map) {
  if (map.size() != state_.cells())
    throw InputError("heating map has " + std::to_string(map.size()) + " values; the grid has " +
                     std::to_string(state_.cells()));
  for (float v : map)
    if (!(v >= 0.0f) || !std::isfinite(v)) throw InputError("heating map values must be finite and ≥ 0");
  for (size_t c = 0; c < map.size(); ++c) heatingMap_[c] *= map[c];
}

glm::dvec2 WeatherModel::prevailingWind_m_s() const {
  double from = config_.windFrom_deg * std::numbers::pi / 180.0;
  return -config_.windSpeed_m_s * glm::dvec2(std::sin(from), std::cos(from));
}

glm::dvec2 WeatherModel::windShear_per_s() const {
  glm::dvec2 u = prevailingWind_m_s();
  double speed = glm::length(u);
  glm::dvec2 direction = speed > 0.0 ? u / speed : glm::dvec2(1.0, 0.0);
  return direction * (config_.windShear_m_s_per_km * 1e-3);
}

double WeatherModel::backgroundVapour_kg_m2(const PresetParameters& p) const {
  BoundaryLayer layer(p, config_.surfacePressure_Pa);
  double e = std::clamp(p.relativeHumidity, 0.0, 1.0) * saturationVapourPressure(p.referenceTemperature_K);
  return layer.massPerArea_kg_m2 * mixingRatioFromVapourPressure(e, config_.surfacePressure_Pa);
}

double WeatherModel::updateWind(const PresetParameters& p) {
  WindParameters w;
  glm::dvec2 u = prevailingWind_m_s();
  w.prevailingU_m_s = u.x;
  w.prevailingV_m_s = u.y;
  w.turbulence_m_s = config_.turbulence_m_s;
  w.boundaryLayerDepth_m = p.boundaryLayerDepth_m;
  w.seed = config_.seed;
  return wind_.update(state_, w, state_.time_s);
}

PresetParameters WeatherModel::withDepth(PresetParameters p, double depth_m) {
  p.boundaryLayerDepth_m = depth_m;
  return p;
}

void WeatherModel::refreshParcelTable(const PresetParameters& layerParameters) {
  // The sounding sees the layer depth in 25 m steps, so a growing layer rebuilds the table every 25 m
  // (or 300 s), not every step.
  const PresetParameters p = withDepth(layerParameters, 25.0 * std::round(layerParameters.boundaryLayerDepth_m / 25.0));
  auto values = p.toArray();
  double change = 0.0;
  for (int i = 0; i < PresetParameters::kCount; ++i)
    change = std::max(change, std::fabs(values[i] - tableParameters_[i]) / std::max(1e-3, std::fabs(values[i])));
  if (tableBuilt_ && (change < 1e-9 || (change < 0.05 && state_.time_s - tableBuiltAt_s_ < 300.0))) return;
  parcelTable_.build(Sounding(p, config_.surfacePressure_Pa));
  tableParameters_ = values;
  tableBuiltAt_s_ = state_.time_s;
  tableBuilt_ = true;
}

void WeatherModel::step(double dt_s) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) throw InputError("weather time step must be positive and finite");
  PresetParameters p = currentParameters();
  OperatorClock clock(times_, timing_);
  double deformation = updateWind(p);
  clock.charge(0);
  double longest = std::min(kMaxSubstep_s, deformation > 0.0 ? 0.5 / deformation : kMaxSubstep_s);
  int n = int(std::min(1e7, std::ceil(dt_s / longest - 1e-9)));
  n = std::max(n, 1);
  lastSubsteps_ = n;
  for (int k = 0; k < n; ++k) substep(dt_s / n, k == 0);
}

void WeatherModel::advance(double duration_s) {
  double end = state_.time_s + duration_s;
  while (state_.time_s < end - 1e-6) step(std::min(config_.timeStep_s, end - state_.time_s));
}

void WeatherModel::substep(double dt, bool windCurrent) {
  WeatherState& s = state_;
  OperatorClock clock(times_, timing_);
  const PresetParameters preset = schedule_.parametersAt(s.time_s);

  // The mixed layer's depth follows the heat the ground has given it today.
  LayerGrowthParameters growth;
  growth.morningDepth_m = preset.boundaryLayerDepth_m;
  growth.freeLapseRate_K_m = preset.lapseRate_K_per_km * 1e-3;
  growth.stableLayerBase_m = preset.stableLayerBase_m;
  growth.exchangeWithSurroundings = config_.exchangeWithSurroundings;
  {
    const BoundaryLayer now(withDepth(preset, s.layerDepth_m), config_.surfacePressure_Pa);
    growth.density_kg_m3 = now.density_kg_m3;
    // Air just above the inversion at the free troposphere's humidity.
    const Sounding sounding(withDepth(preset, s.layerDepth_m), config_.surfacePressure_Pa);
    growth.entrainedMixingRatio =
        std::clamp(preset.freeTroposphereRH, 0.0, 1.0) *
        saturationMixingRatio(sounding.temperatureAt(s.layerDepth_m + 1.0), now.topPressure_Pa);
  }
  s.exchangedIn_kg += applyLayerGrowth(s, growth, dt);
  const PresetParameters p = withDepth(preset, s.layerDepth_m);
  refreshParcelTable(p);
  const BoundaryLayer layer(p, config_.surfacePressure_Pa);
  clock.charge(7);
  if (!windCurrent) updateWind(p);
  clock.charge(0);

  // Transport (transport.h). Fields that are zero everywhere (no cloud yet) are not advected. Water gets
  // one mass fix after advection and mixing together, which also settles the previous step's
  // pendingVapour (remnants returned, vapour drawn into storms from their catchment).
  const double owed = s.pendingVapour;
  s.pendingVapour = 0.0;
  transport_.advect(s, dt);
  clock.charge(1);
  transport_.mixAndConserve(s, kMixingDiffusivity_m2_s, dt, owed);
  clock.charge(2);

  // Sources.
  SurfaceHeatingParameters heating;
  heating.sunElevation_rad = sunElevation_(s.time_s + 0.5 * dt);
  heating.absorbedSolar_W_m2 = p.absorbedSolar_W_m2 * config_.heatingScale;
  heating.bowenRatio = p.bowenRatio;
  heating.backgroundVapour_kg_m2 = backgroundVapour_kg_m2(p);
  heating.exchangeWithSurroundings = config_.exchangeWithSurroundings;
  s.exchangedIn_kg += applySurfaceHeating(s, heatingMap_, layer, heating, dt);
  clock.charge(3);

  StratiformParameters stratiform;
  stratiform.largeScaleLift_m_s = p.largeScaleLift_m_s;
  stratiform.frontLift_m_s = p.frontLift_m_s;
  stratiform.frontWidth_m = p.frontWidth_m;
  glm::dvec2 u = prevailingWind_m_s();
  double speed = glm::length(u);
  glm::dvec2 direction = speed > 0.0 ? u / speed : glm::dvec2(1.0, 0.0);
  stratiform.frontDirectionX = direction.x;
  stratiform.frontDirectionY = direction.y;
  stratiform.frontPosition_m = speed * s.time_s;
  stratiform.freeTroposphereRH = p.freeTroposphereRH;
  applyStratiform(s, layer, stratiform, dt, columnScratch_);
  clock.charge(4);

  ConvectionParameters convection;
  convection.tropopause_m = std::max(p.tropopause_m, p.stableLayerBase_m);
  convection.subsidenceWarming_K = &subsidenceWarming_;
  const ConvectionResult convected = applyConvection(s, parcelTable_, layer, convection, dt, columnScratch_);
  s.meanMassFlux_m_s = convected.massFlux_m_s;
  s.pendingVapour -= convected.drawnVapour;  // taken from the catchment at the next mass fix
  subsidence_.apply(s, kConvectiveCoreFraction, p.lapseRate_K_per_km * 1e-3, dt, subsidenceWarming_);
  s.subsidenceWarming_K = subsidence_.domainMean_K();
  clock.charge(5);

  s.precipitatedOut_kg += applyMicrophysics(s, layer, dt, columnScratch_);
  clock.charge(6);

  // Housekeeping: remnants of cloud and rain below 1e-3 kg/m² (cloud optical depth ≈ 0.15, cover 0.02;
  // rain below 0.02 mm/h) evaporate instead of decaying forever (their sum goes back to the vapour field
  // at the next mass fix, in double, so no water is lost to rounding). They are the thin tails that
  // mixing and interpolation spread around every cloud, and at 1e-4 kg/m² they kept half the domain in
  // the cloud and rain operators for nothing visible. Tops only where there is cloud; the anomaly within
  // the parcel table's range.
  constexpr float kRemnant = 1e-3f;
  double remnants = 0.0;
  const size_t n = s.cells();
  size_t start = 0;
#if defined(__SSE2__)
  // Four cells at a time, the scalar loop's selects; the remnants summed in two pairs of double lanes (a
  // different order than one running sum: round-off).
  {
    using namespace sse;
    const F4 zero = _mm_setzero_ps(), remnant = set1(kRemnant), one = set1(1.0f);
    __m128d sumLo = _mm_setzero_pd(), sumHi = _mm_setzero_pd();
    for (; start + 4 <= n; start += 4) {
      const size_t c = start;
      _mm_storeu_ps(&s.temperature[c], clampStd(_mm_loadu_ps(&s.temperature[c]), set1(-30.0f), set1(30.0f)));
      const F4 cloud = _mm_loadu_ps(&s.cloudWater[c]), rain = _mm_loadu_ps(&s.rain[c]);
      const F4 top = _mm_loadu_ps(&s.cloudTop[c]), conv = _mm_loadu_ps(&s.convectiveFraction[c]);
      const F4 bare = _mm_and_ps(_mm_and_ps(_mm_cmpeq_ps(cloud, zero), _mm_cmpeq_ps(rain, zero)),
                                 _mm_and_ps(_mm_cmpeq_ps(top, zero), _mm_cmpeq_ps(conv, zero)));
      if (_mm_movemask_ps(bare) == 0xF) continue;
      const F4 cloudGone = _mm_and_ps(_mm_cmpgt_ps(cloud, zero), _mm_cmplt_ps(cloud, remnant));
      const F4 rainGone = _mm_and_ps(_mm_cmpgt_ps(rain, zero), _mm_cmplt_ps(rain, remnant));
      const F4 cloudLeft = _mm_andnot_ps(cloudGone, cloud), rainLeft = _mm_andnot_ps(rainGone, rain);
      // The remnants, summed as doubles (a float sum of the two could round).
      const F4 cloudRem = _mm_and_ps(cloudGone, cloud), rainRem = _mm_and_ps(rainGone, rain);
      sumLo = _mm_add_pd(sumLo, _mm_add_pd(_mm_cvtps_pd(cloudRem), _mm_cvtps_pd(rainRem)));
      sumHi = _mm_add_pd(sumHi, _mm_add_pd(_mm_cvtps_pd(_mm_movehl_ps(cloudRem, cloudRem)),
                                           _mm_cvtps_pd(_mm_movehl_ps(rainRem, rainRem))));
      const F4 clear = _mm_andnot_ps(bare, _mm_and_ps(_mm_cmpeq_ps(cloudLeft, zero), _mm_cmpeq_ps(rainLeft, zero)));
      _mm_storeu_ps(&s.cloudWater[c], cloudLeft);
      _mm_storeu_ps(&s.rain[c], rainLeft);
      _mm_storeu_ps(&s.cloudTop[c], _mm_andnot_ps(clear, top));
      // Bare lanes keep conv (0): clamp of 0 is 0.
      _mm_storeu_ps(&s.convectiveFraction[c], clampStd(_mm_andnot_ps(clear, conv), zero, one));
    }
    alignas(16) double parts[4];
    _mm_store_pd(parts, sumLo);
    _mm_store_pd(parts + 2, sumHi);
    remnants = (parts[0] + parts[1]) + (parts[2] + parts[3]);
  }
#endif
  for (size_t c = start; c < n; ++c) {
    s.temperature[c] = std::clamp(s.temperature[c], -30.0f, 30.0f);
    float cloud = s.cloudWater[c], rain = s.rain[c];
    if (cloud == 0.0f && rain == 0.0f && s.cloudTop[c] == 0.0f && s.convectiveFraction[c] == 0.0f) continue;
    if (cloud > 0.0f && cloud < kRemnant) {
      remnants += cloud;
      s.cloudWater[c] = cloud = 0.0f;
    }
    if (rain > 0.0f && rain < kRemnant) {
      remnants += rain;
      s.rain[c] = rain = 0.0f;
    }
    if (cloud == 0.0f && rain == 0.0f) {
      s.cloudTop[c] = 0.0f;
      s.convectiveFraction[c] = 0.0f;
    }
    s.convectiveFraction[c] = std::clamp(s.convectiveFraction[c], 0.0f, 1.0f);
  }
  s.pendingVapour += remnants;
  s.time_s += dt;
  clock.charge(7);
}

WeatherMap WeatherModel::map(const RegionPlacement& placement) const {
  return makeWeatherMap(state_, placement, windShear_per_s());
}

WaterBudget WeatherModel::waterBudget() const {
  WaterBudget b;
  b.total_kg = state_.waterTotal_kg();
  b.precipitatedOut_kg = state_.precipitatedOut_kg;
  b.exchangedIn_kg = state_.exchangedIn_kg;
  b.initial_kg = initialWater_kg_;
  return b;
}

void WeatherModel::resetBudget() {
  state_.precipitatedOut_kg = 0.0;
  state_.exchangedIn_kg = 0.0;
  initialWater_kg_ = state_.waterTotal_kg();
}

}  // namespace firmament::weather
