#pragma once
// The model's fields on a periodic nx × ny grid of square cells, flat row-major float arrays (j = 0 is
// the southern row, i = 0 the western column). Water is held as column amounts in kg/m², so a domain
// total is Σ · cellArea and its conservation is exact to round-off.
#include <cstddef>
#include <vector>

namespace firmament::weather {

using Field = std::vector<float>;

// Moves a non-negative `amount` (≤ from) of water from one cell value to another so that the receiver
// gains exactly what the giver loses in float arithmetic. Plain `from -= a; to += a` creates or destroys
// water whenever a is below half an ulp of either side (a trace of cloud evaporating into a large vapour
// path), and such errors are biased, not random. The move is trimmed to what both sides can represent;
// when nothing can move exactly (a trace far below the receiver's resolution) nothing moves.
inline void transferWater(float& from, float& to, float amount) {
  if (!(amount > 0.0f)) return;
  amount = amount < from ? amount : from;
  float newTo = to + amount;
  float gained = newTo - to;
  if (gained <= from) {
    float newFrom = from - gained;
    if (from - newFrom == gained) {
      from = newFrom;
      to = newTo;
      return;
    }
  }
  float newFrom = from - amount;
  float lost = from - newFrom;
  newTo = to + lost;
  if (newTo - to == lost) {
    from = newFrom;
    to = newTo;
  }
}

// Σ of a field in double precision.
double sumField(const Field& f);
// Whether any value is non-zero (NaN counts as non-zero).
bool anyNonZero(const Field& f);

struct WeatherState {
  int nx = 0, ny = 0;
  double cellSize_m = 200.0;
  double time_s = 0.0;

  // Prognostic.
  Field temperature;         // boundary-layer temperature anomaly against the preset's reference (K)
  Field vapour;              // boundary-layer water vapour path (kg/m²)
  Field cloudWater;          // cloud liquid water path (kg/m²)
  Field rain;                // rain water path aloft (kg/m²)
  Field updraft;             // convective updraft strength (m/s)
  Field cloudTop;            // cloud-top height above ground (m); 0 where there is no cloud
  Field convectiveFraction;  // share of the cloud water that is convective (0 stratiform … 1 convective)

  // Diagnostic (recomputed every step).
  Field cloudBase;          // m above ground (lifting condensation level)
  Field surfaceHeatFlux;    // sensible heat flux (W/m²)
  Field precipitationRate;  // rain reaching the ground (kg m⁻² s⁻¹ = mm/s)
  Field windU, windV;       // total wind at cloud base, east and north (m/s)
  Field lift;               // ascent at the boundary-layer top from convergence and large-scale lifting (m/s)

  // Domain-wide state of the layer and its environment.
  double layerDepth_m = 1000.0;        // mixed-layer depth h (boundary_layer_growth.h)
  double meanSensibleHeat_W_m2 = 0.0;  // domain mean of surfaceHeatFlux, last step
  double subsidenceWarming_K = 0.0;    // domain mean of δ, compensating_subsidence.h
  double meanMassFlux_m_s = 0.0;       // σ w̄ of the last convection step

  // Water that left or entered the domain, integrated (kg).
  double precipitatedOut_kg = 0.0;
  double exchangedIn_kg = 0.0;  // surface evaporation, entrainment and detrainment
  // Vapour owed to (positive) or by (negative) the vapour field, Σ over cells of kg/m²: remnants of
  // cloud and rain evaporated, minus vapour storms drew from their catchment; the next mass fix
  // settles it (weather_model.cpp).
  double pendingVapour = 0.0;

  WeatherState() = default;
  WeatherState(int nx_, int ny_, double cellSize);
  size_t cells() const { return size_t(nx) * size_t(ny); }
  double cellArea() const { return cellSize_m * cellSize_m; }
  size_t index(int i, int j) const { return size_t(j) * size_t(nx) + size_t(i); }
  // Σ field · cellArea in double.
  double total_kg(const Field& f) const;
  double waterTotal_kg() const {
    return total_kg(vapour) + total_kg(cloudWater) + total_kg(rain) + pendingVapour * cellArea();
  }
};

}  // namespace firmament::weather
