#pragma once
// One sub-step's transport of the model's fields (weather_model.cpp, steps 2 and 3): semi-Lagrangian
// advection of every non-empty field (advection.h), mixing of T′, vapour and cloud (mixing.h), and one
// mass fix for the water fields (SemiLagrangianAdvection::restoreTotal) that also settles the vapour
// owed by or to the vapour field.
//
// On grids whose interleaved copies fit in cache (256²) the three run fused: the fields are interleaved
// once (with the water totals summed on the way), the bilinear interpolation of the departure points
// runs four fields per vector, the mixing's five-point stencil runs on the interleaved result (T′,
// vapour, cloud and rain in one vector, rain passed through) and writes the fields back with their new
// totals summed, and the mass fixer gets those totals. Every value is computed with the same operations
// in the same order as the separate operators (advection, then mixing, then the fixer), so the result
// is the same bit for bit; what goes away is ten passes over the fields and their memory traffic.
// Larger grids and targets without SSE2 run the separate operators.
#include <cstdint>
#include <vector>

#include "weather/advection.h"
#include "weather/domain_sum.h"
#include "weather/mixing.h"
#include "weather/weather_state.h"

namespace firmament::weather {

class Transport {
 public:
  // Advects the state's fields with its wind (windU, windV) over dt, and remembers the water totals
  // before (Σ of cell values) for the mass fix.
  void advect(WeatherState& s, double dt_s);
  // Mixes T′, vapour and (where there was cloud) cloud water with diffusivity K, then restores the water
  // fields to their totals before advect(), the vapour's plus `vapourOwed` (Σ over cells, kg/m²).
  void mixAndConserve(WeatherState& s, double diffusivity_m2_s, double dt_s, double vapourOwed);

 private:
  bool fusedGrid(const WeatherState& s) const;
  void advectInterleaved(WeatherState& s, double dt_s);
  void mixInterleaved(WeatherState& s, double diffusivity_m2_s, double dt_s, double vapourOwed);
#if defined(__SSE2__)
  template <int V>
  void sweep(WeatherState& s, double dt_s, sse::DomainSum& rainSum);
#endif

  SemiLagrangianAdvection advection_;
  Mixing mixing_;
  // Totals before advection, and which fields the step carries.
  double vapourBefore_ = 0.0, cloudBefore_ = 0.0, rainBefore_ = 0.0, rainAfter_ = 0.0;
  bool wet_ = false;    // cloud or rain somewhere: advected
  bool fused_ = false;  // the last advect() left T′, vapour and cloud in mixT_, mixQ_, mixC_ (fused path)
  // Fused path: the interleaved input (4 or 8 floats per cell: T′, vapour, cloud, rain | updraft, top,
  // convective fraction, 0; a 16-byte aligned view into the buffer), the advected fields that mix, and a
  // spare field for mixing in more than one iteration.
  std::vector<float> packedBuffer_;
  float* packed_ = nullptr;
  Field mixT_, mixQ_, mixC_, spare_;
  // One row's departure cells and fractions.
  std::vector<int32_t> rowI_, rowJ_;
  std::vector<float> rowFx_, rowFy_;
};

}  // namespace firmament::weather
