#pragma once
// Horizontal mixing by unresolved turbulence: ∂q/∂t = K ∇²q, five-point Laplacian in flux form on the
// periodic grid (what leaves a cell enters its neighbour, so Σq is unchanged). The explicit update is
// stable for K Δt/Δx² ≤ 1/4; a longer step is split into as many equal iterations as that needs.
// K ≈ 100 m²/s is a typical horizontal eddy diffusivity at a few hundred metres (Stull 1988, §6).
#include "weather/weather_state.h"

namespace firmament::weather {

class Mixing {
 public:
  // Returns the number of explicit iterations used.
  int apply(Field& f, int nx, int ny, double cellSize_m, double diffusivity_m2_s, double dt_s);

 private:
  Field scratch_;
};

}  // namespace firmament::weather
