#pragma once
// The weather model: a periodic 2D boundary layer under a preset's sounding, stepped by operator
// splitting (docs/weather.md). One step of Δt runs, in order: mixed-layer growth → wind → advection →
// mixing (+ mass fixer) → surface heating → large-scale lifting and stratiform condensation → convection
// (+ compensating subsidence) → rain.
//
// Stability: every operator is unconditionally stable on its own (semi-Lagrangian advection; exact
// exponential integration of relaxations and conversions; mixing iterates to K Δt/Δx² ≤ 0.2). A
// requested step is split into n equal sub-steps with Δt/n ≤ 120 s (the fastest physical time scale the
// operator splitting resolves, the updraft's spin-up) and Δt/n · max|∇u| ≤ 0.5 (no crossing
// trajectories), so any step, a day included, stays stable.
#include <cstdint>
#include <vector>

#include "weather/active_cells.h"
#include "weather/compensating_subsidence.h"
#include "weather/parcel_table.h"
#include "weather/preset_schedule.h"
#include "weather/sun_elevation.h"
#include "weather/transport.h"
#include "weather/weather_config.h"
#include "weather/weather_map.h"
#include "weather/weather_state.h"
#include "weather/weather_stats.h"
#include "weather/wind_field.h"

namespace firmament::weather {

struct WaterBudget {
  double total_kg = 0.0;  // vapour + cloud + rain in the domain now
  double precipitatedOut_kg = 0.0;
  double exchangedIn_kg = 0.0;
  double initial_kg = 0.0;
  // total + out − in − initial: zero for exact conservation.
  double imbalance_kg() const { return total_kg + precipitatedOut_kg - exchangedIn_kg - initial_kg; }
};

// CPU time spent in each operator (seconds, summed over sub-steps), for the benchmark's breakdown;
// collected only when enabled (one clock read per operator per sub-step).
struct OperatorTimes {
  static constexpr int kCount = 8;
  static constexpr const char* kNames[kCount] = {"wind",       "advection",  "mixing", "surface heating",
                                                 "stratiform", "convection", "rain",   "housekeeping"};
  double seconds[kCount] = {};
};

class WeatherModel {
 public:
  static constexpr double kMaxSubstep_s = 120.0;
  static constexpr double kMixingDiffusivity_m2_s = 100.0;
  static constexpr double kConvectiveCoreFraction = 0.1;  // σ, convection.h

  WeatherModel(const WeatherConfig& config, SunElevationFunction sunElevation);

  // Advances by dt (any positive length; sub-stepped as needed).
  void step(double dt_s);
  // Advances by `duration` in steps of config.timeStep_s (the last one shortened).
  void advance(double duration_s);

  // A heating multiplier per cell (row-major, j = 0 south), e.g. 1 on land and 0.2 on water; it
  // multiplies the seeded heterogeneity. Throws InputError on a size mismatch or negative values.
  void setHeatingMap(const std::vector<float>& map);

  const WeatherState& state() const { return state_; }
  WeatherState& mutableState() { return state_; }  // tests: initial blobs, saturated/bone-dry air
  const WeatherConfig& config() const { return config_; }
  double time_s() const { return state_.time_s; }
  int lastSubsteps() const { return lastSubsteps_; }
  // The parameters in effect now, with the mixed layer at its current depth.
  PresetParameters currentParameters() const {
    return withDepth(schedule_.parametersAt(state_.time_s), state_.layerDepth_m);
  }
  double layerDepth_m() const { return state_.layerDepth_m; }
  double subsidenceWarming_K() const { return state_.subsidenceWarming_K; }

  WeatherMap map(const RegionPlacement& placement = {}) const;
  void enableOperatorTimes(bool on) { timing_ = on; }
  const OperatorTimes& operatorTimes() const { return times_; }
  WeatherStats stats() const { return computeStats(state_); }
  WaterBudget waterBudget() const;
  // Rebases the budget's initial total (after a test edits the state).
  void resetBudget();

  // Prevailing wind (east, north) at cloud base and its shear (per second).
  glm::dvec2 prevailingWind_m_s() const;
  glm::dvec2 windShear_per_s() const;
  // Background boundary-layer vapour path for a parameter set (kg/m²).
  double backgroundVapour_kg_m2(const PresetParameters& p) const;

 private:
  void substep(double dt_s, bool windCurrent);
  double updateWind(const PresetParameters& p);
  void refreshParcelTable(const PresetParameters& p);
  static PresetParameters withDepth(PresetParameters p, double depth_m);

  WeatherConfig config_;
  SunElevationFunction sunElevation_;
  PresetSchedule schedule_;
  WeatherState state_;
  Field heatingMap_, userHeatingMap_;
  WindField wind_;
  CompensatingSubsidence subsidence_;
  Field subsidenceWarming_;
  Transport transport_;
  ColumnScratch columnScratch_;
  ParcelTable parcelTable_;
  std::array<double, PresetParameters::kCount> tableParameters_{};
  double tableBuiltAt_s_ = -1e30;
  bool tableBuilt_ = false;
  double initialWater_kg_ = 0.0;
  int lastSubsteps_ = 0;
  bool timing_ = false;
  OperatorTimes times_;
};

}  // namespace firmament::weather
