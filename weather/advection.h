#pragma once
// Semi-Lagrangian advection (Staniforth & Côté 1991, MWR 119:2206): the value arriving at a cell centre
// x is the field interpolated (bilinearly, periodic) at the departure point x − u(x) Δt. It is stable for
// any Δt (no CFL limit); it needs Δt · max|∇u| < 1 for trajectories not to cross, which the model's
// sub-stepping guarantees.
//
// Semi-Lagrangian interpolation does not conserve mass. For water, a global a-posteriori fixer
// (Priestley 1993, MWR 121:621) rescales the field to its pre-advection total: q ← q · Σq⁻/Σq⁺, which
// keeps positive fields positive and makes the domain total exact to round-off (the per-cell rounding
// of the rescale is carried from cell to cell, so the total is right to a float ulp of one cell).
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "weather/weather_state.h"

namespace firmament::weather {

class SemiLagrangianAdvection {
 public:
  // Computes the departure points of every cell for this wind and step (shared by all fields).
  //
  // A departure point is x − d, d = u Δt/Δx in cells. Within 64 cells (any sub-step of the model: at
  // most 120 s at 60 m/s on 200 m cells is 36) d is computed in float and split into the integer cell
  // offset and the fraction exactly, so the fraction carries d's own rounding, ≤ 6e-8 |d| (2e-6 of a cell
  // at 36 cells); farther ones (a long step in one go) are computed from the cell position in double.
  void prepare(const Field& windU, const Field& windV, int nx, int ny, double cellSize_m, double dt_s);
  // The departure points of row j alone (what prepare() stores for every row): the cell west and south of
  // the departure point, wrapped into the grid, and the fractions (0 ≤ f ≤ 1) within it.
  static void departureRow(int j, const float* windU, const float* windV, int nx, int ny, double scale, int32_t* cellI,
                           int32_t* cellJ, float* fx, float* fy);
  // Advects f in place (scratch is resized as needed).
  void advect(Field& f);
  // Advects and restores the domain total (the mass fixer). Returns the relative correction applied.
  double advectConserving(Field& f);
  // The same for several fields in one pass (at most 8).
  void advectFields(std::initializer_list<Field*> fields);
  void advectConservingFields(std::initializer_list<Field*> fields);
  // Rescales f to the total `before` (Σ of values, double). Returns the relative correction.
  static double restoreTotal(Field& f, double before);
  // The same with the field's present Σ (sumField(f)) already known.
  static double restoreTotal(Field& f, double before, double after);

 private:
  int nx_ = 0, ny_ = 0;
  std::vector<int32_t> i0_, j0_;
  std::vector<float> fx_, fy_;
  std::vector<Field> scratchMany_;
  Field packed_;  // several fields interleaved, 4 or 8 floats per cell (advectFields)
  Field zeros_;   // the lanes of the interleaved fields that no field fills
};

}  // namespace firmament::weather
