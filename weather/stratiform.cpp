#include "weather/stratiform.h"

#include <algorithm>
#include <cmath>

#include "weather/fast_math_sse.h"
#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {
namespace {

// Cells with work: cloud to evaporate, or vapour above a lower bound of the saturation path
// W_sat(T′) ≥ s₀ + s₁ T′ (the tangent at T′ = 0: r_s is convex in T, and the tabulated e_s interpolates a
// convex function from above, so the line is below every value the update compares with; the bound is
// lowered by 1e-4 relative more for float rounding). Branch-free; restrict parameters, which GCC trusts
// here and not on pointers taken from vectors inside the caller.
void markColumns(size_t n, float s0, float s1, const float* __restrict anomaly, const float* __restrict vapour,
                 const float* __restrict cloud, uint8_t* __restrict active) {
  for (size_t c = 0; c < n; ++c) active[c] = uint8_t((cloud[c] > 0.0f) | (vapour[c] > s0 + s1 * anomaly[c]));
}

}  // namespace

void applyStratiform(WeatherState& s, const BoundaryLayer& layer, const StratiformParameters& p, double dt_s,
                     ColumnScratch& work) {
  constexpr double kCondensationTime_s = 300.0, kEvaporationTime_s = 600.0;
  const float condense = float(1.0 - std::exp(-dt_s / kCondensationTime_s));
  const float evaporate = float(1.0 - std::exp(-dt_s / kEvaporationTime_s));
  const float kelvinPerKg = float(kLatentHeatVaporization / layer.heatCapacity_J_m2_K);
  const float topCooling = float(kDryAdiabaticLapseRate * layer.depth_m);
  const float rhoH = float(layer.massPerArea_kg_m2);
  const float topPressure = float(layer.topPressure_Pa);
  const float depth = float(layer.depth_m);
  const float ftDeficit = float(std::clamp(1.0 - p.freeTroposphereRH, 0.0, 1.0));
  const double lx = s.nx * s.cellSize_m, ly = s.ny * s.cellSize_m;
  const double period = std::fabs(p.frontDirectionX) * lx + std::fabs(p.frontDirectionY) * ly;
  const bool lifting = p.largeScaleLift_m_s != 0.0 || (p.frontLift_m_s != 0.0 && period > 0.0);
  const size_t n = s.cells();
  // Large-scale ascent and its adiabatic cooling, with the frontal band at periodic distance d along the
  // front's motion.
  // (Without lifting the ascent is the same everywhere and is not stored.)
  Field& lift = work.value[0];
  const float uniformLift = float(p.largeScaleLift_m_s);
  if (lifting) {
    lift.assign(n, uniformLift);
    for (int j = 0; j < s.ny; ++j) {
      for (int i = 0; i < s.nx; ++i) {
        size_t c = s.index(i, j);
        float w = float(p.largeScaleLift_m_s);
        if (p.frontLift_m_s != 0.0 && period > 0.0) {
          double along = ((i + 0.5) * p.frontDirectionX + (j + 0.5) * p.frontDirectionY) * s.cellSize_m;
          double d = std::remainder(along - p.frontPosition_m, period);
          w += float(p.frontLift_m_s * std::exp(-(d * d) / (p.frontWidth_m * p.frontWidth_m)));
        }
        lift[c] = w;
        s.lift[c] += w;
        s.temperature[c] -= float(kDryAdiabaticLapseRate) * w * float(dt_s);
      }
    }
  }

  // Tangent of W_sat at T′ = 0 (double; the slope from d ln e_s/dT = 17.27 · 237.3/(T − 35.85)² and
  // dr/de = ε p/(p − e)²).
  const double t0 = layer.referenceTemperature_K - kDryAdiabaticLapseRate * layer.depth_m;
  const double p1 = layer.topPressure_Pa, e0 = saturationVapourPressure(t0);
  const double slopeE = e0 * 17.27 * (273.15 - 35.85) / ((t0 - 35.85) * (t0 - 35.85));
  const float s0 = float(layer.massPerArea_kg_m2 * saturationMixingRatio(t0, p1) * (1.0 - 1e-4));
  const float s1 = float(layer.massPerArea_kg_m2 * kEpsilon * p1 / ((p1 - e0) * (p1 - e0)) * slopeE);
  size_t start = 0;
#if defined(__SSE2__)
  // Four cells at a time, the same operations as the scalar update below lane by lane (fast_math_sse.h),
  // its branches as selects; four cells without work (the bound above) are skipped.
  {
    using namespace sse;
    const F4 zero = _mm_setzero_ps(), one = set1(1.0f);
    const F4 tRef = set1(float(layer.referenceTemperature_K)), topCoolingV = set1(topCooling);
    const F4 topPressureV = set1(topPressure), rhoHV = set1(rhoH);
    float* anomalyT = s.temperature.data();
    float* vapourW = s.vapour.data();
    float* cloudW = s.cloudWater.data();
    float* convective = s.convectiveFraction.data();
    float* cloudTop = s.cloudTop.data();
    const float* ascent = lifting ? lift.data() : nullptr;
    const F4 uniformAscent = set1(uniformLift);
    // In chunks of 256 cells: first the saturation path of every cell (a loop without branches whose
    // table loads and division the processor overlaps over many cells), then the update where there is
    // work.
    constexpr size_t kChunk = 256;
    alignas(16) F4 saturatedOf[kChunk / 4];
    for (size_t chunk = 0; chunk + 4 <= n; chunk += kChunk) {
      const size_t end = std::min(n - n % 4, chunk + kChunk);
      for (size_t c = chunk; c < end; c += 4)
        saturatedOf[(c - chunk) / 4] =
            _mm_mul_ps(rhoHV, saturationMixingRatioFast4(
                                  _mm_sub_ps(_mm_add_ps(tRef, _mm_loadu_ps(anomalyT + c)), topCoolingV), topPressureV));
      for (start = chunk; start < end; start += 4) {
        const size_t c = start;
        const F4 anomaly = _mm_loadu_ps(anomalyT + c), vapour = _mm_loadu_ps(vapourW + c),
                 cloud = _mm_loadu_ps(cloudW + c);
        const F4 cloudy = _mm_cmpgt_ps(cloud, zero);
        if (_mm_movemask_ps(
                _mm_or_ps(cloudy, _mm_cmpgt_ps(vapour, _mm_add_ps(set1(s0), _mm_mul_ps(set1(s1), anomaly))))) == 0)
          continue;
        const F4 conv = _mm_loadu_ps(convective + c), top = _mm_loadu_ps(cloudTop + c);
        const F4 saturated = saturatedOf[(c - chunk) / 4];
        const F4 condensing = _mm_cmpgt_ps(vapour, saturated);
        const F4 evaporating = _mm_andnot_ps(condensing, cloudy);
        const F4 dq = _mm_mul_ps(_mm_sub_ps(vapour, saturated), set1(condense));
        const F4 layerDeficit = select(_mm_cmpgt_ps(saturated, zero),
                                       clampStd(_mm_sub_ps(one, _mm_div_ps(vapour, saturated)), zero, one), one);
        const F4 stratiformShare = _mm_sub_ps(one, conv);
        const F4 e =
            _mm_mul_ps(_mm_mul_ps(cloud, set1(evaporate)),
                       _mm_add_ps(_mm_mul_ps(conv, set1(ftDeficit)), _mm_mul_ps(stratiformShare, layerDeficit)));
        F4 from = select(condensing, vapour, cloud), to = select(condensing, cloud, vapour);
        transferWater(from, to, select(condensing, dq, _mm_and_ps(evaporating, e)));
        _mm_storeu_ps(vapourW + c, select(condensing, from, to));
        _mm_storeu_ps(cloudW + c, select(condensing, to, from));
        const F4 warmed = _mm_add_ps(anomaly, _mm_mul_ps(set1(kelvinPerKg), dq));
        const F4 cooled = _mm_sub_ps(anomaly, _mm_mul_ps(_mm_mul_ps(stratiformShare, set1(kelvinPerKg)), e));
        _mm_storeu_ps(anomalyT + c, select(condensing, warmed, select(evaporating, cooled, anomaly)));
        const F4 total = _mm_add_ps(cloud, dq);
        const F4 mixedShare = _mm_and_ps(_mm_cmpgt_ps(total, zero), _mm_div_ps(_mm_mul_ps(conv, cloud), total));
        _mm_storeu_ps(convective + c, select(condensing, mixedShare, conv));
        const F4 stratiformTop =
            _mm_add_ps(set1(depth),
                       minStd(set1(8000.0f),
                              _mm_mul_ps(maxStd(ascent ? _mm_loadu_ps(ascent + c) : uniformAscent, zero), set1(1e5f))));
        const F4 lower = _mm_or_ps(_mm_cmplt_ps(conv, set1(0.5f)), _mm_cmplt_ps(top, stratiformTop));
        _mm_storeu_ps(cloudTop + c,
                      select(_mm_and_ps(condensing, lower), maxStd(_mm_mul_ps(top, conv), stratiformTop), top));
      }
    }
  }
#endif
  // The remaining cells (all of them without SSE2): those with work, then the update.
  work.active.assign(n - start, 0);
  markColumns(n - start, s0, s1, s.temperature.data() + start, s.vapour.data() + start, s.cloudWater.data() + start,
              work.active.data());

  forEachActiveCell(work.active, [&](size_t k) {
    const size_t c = start + k;
    const float w = lifting ? lift[c] : uniformLift;
    float topTemperature = float(layer.referenceTemperature_K) + s.temperature[c] - topCooling;
    float saturated = rhoH * saturationMixingRatioFast(topTemperature, topPressure);
    float vapour = s.vapour[c], cloud = s.cloudWater[c], conv = s.convectiveFraction[c];
    if (vapour > saturated) {
      float dq = (vapour - saturated) * condense;
      transferWater(s.vapour[c], s.cloudWater[c], dq);
      s.temperature[c] += kelvinPerKg * dq;
      // The new water is stratiform: the convective share drops by mass weighting.
      s.convectiveFraction[c] = cloud + dq > 0.0f ? conv * cloud / (cloud + dq) : 0.0f;
      float stratiformTop = depth + std::min(8000.0f, std::max(w, 0.0f) * 1e5f);
      if (conv < 0.5f || s.cloudTop[c] < stratiformTop) s.cloudTop[c] = std::max(s.cloudTop[c] * conv, stratiformTop);
    } else if (cloud > 0.0f) {
      float layerDeficit = saturated > 0.0f ? std::clamp(1.0f - vapour / saturated, 0.0f, 1.0f) : 1.0f;
      float e = cloud * evaporate * (conv * ftDeficit + (1.0f - conv) * layerDeficit);
      transferWater(s.cloudWater[c], s.vapour[c], e);
      s.temperature[c] -= (1.0f - conv) * kelvinPerKg * e;
    }
  });
}

}  // namespace firmament::weather
