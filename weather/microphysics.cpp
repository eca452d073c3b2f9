#include "weather/microphysics.h"

#include <algorithm>
#include <cmath>

#include "weather/fast_math.h"
#include "weather/fast_math_sse.h"
#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

double applyMicrophysics(WeatherState& s, const BoundaryLayer& layer, double dt_s, ColumnScratch& work) {
  constexpr float kAutoconversionRate = 1e-3f, kThresholdMixingRatio = 0.5e-3f, kFallSpeed = 6.0f;
  const float dt = float(dt_s);
  const float rho = float(layer.density_kg_m3);
  const float kelvinPerKg = float(kLatentHeatVaporization / layer.heatCapacity_J_m2_K);
  const float rhoH = float(layer.massPerArea_kg_m2);
  const float tRef = float(layer.referenceTemperature_K);
  const float p0 = float(layer.surfacePressure_Pa);
  double out = 0.0;
  const size_t n = s.cells();
  size_t start = 0;
#if defined(__SSE2__)
  // Four cells at a time, every cell: with rain in a third of the domain (storms) the sparse scalar pass
  // below costs several times this. The same operations as the scalar code lane by lane
  // (fast_math_sse.h), with the branches as selects; a lane without work keeps its values. What left the
  // domain is summed in two pairs of double lanes (a different order than the scalar sum: round-off).
  {
    using namespace sse;
    const F4 zero = _mm_setzero_ps(), rhoV = set1(rho);
    const F4 thresholdPerMetre = set1(rho * kThresholdMixingRatio);
    const __m128d dtPair = _mm_set1_pd(dt_s);
    __m128d leftLo = _mm_setzero_pd(), leftHi = _mm_setzero_pd();
    float* cloudW = s.cloudWater.data();
    float* rainW = s.rain.data();
    float* vapourW = s.vapour.data();
    float* anomalyT = s.temperature.data();
    float* rateOut = s.precipitationRate.data();
    const float* baseZ = s.cloudBase.data();
    const float* topZ = s.cloudTop.data();
    // In chunks of 256 cells: first which blocks of four have work (the others get a zero rate), then
    // for those, in loops of their own without branches (each quantity is a long chain of dependent
    // operations, with divisions, a power and exponentials; in short loops the processor overlaps the
    // chains of many blocks), the saturation path, accretion's power, the fall-out share, what converts
    // and the share that evaporates, and then the update.
    constexpr size_t kChunk = 256;
    const F4 allOnes = _mm_castsi128_ps(_mm_set1_epi32(-1));
    alignas(16) F4 saturatedOf[kChunk / 4], accretionOf[kChunk / 4], fallShareOf[kChunk / 4], convertedOf[kChunk / 4],
        evaporatingShareOf[kChunk / 4];
    uint32_t blockOf[kChunk / 4];
    // The layer of the four cells at c: base, top (at least 100 m above the base), depth, and the cloud
    // water that autoconversion leaves (the threshold mixing ratio over the depth, at most 2 km of it).
    struct Column {
      F4 base, top, depth, threshold;
    };
    auto columnAt = [&](size_t c) {
      Column k;
      k.base = _mm_loadu_ps(baseZ + c);
      k.top = maxStd(_mm_loadu_ps(topZ + c), _mm_add_ps(k.base, set1(100.0f)));
      k.depth = _mm_sub_ps(k.top, k.base);
      k.threshold = _mm_mul_ps(thresholdPerMetre, minStd(k.depth, set1(2000.0f)));
      return k;
    };
    // Cells with work: some cloud or rain, unless there is no rain and the cloud is at most the threshold.
    auto activeMask = [&](F4 cloud, F4 rain, F4 threshold) {
      const F4 empty = _mm_and_ps(_mm_cmple_ps(cloud, zero), _mm_cmple_ps(rain, zero));
      const F4 idle = _mm_and_ps(_mm_cmpeq_ps(rain, zero), _mm_cmple_ps(cloud, threshold));
      return _mm_andnot_ps(_mm_or_ps(empty, idle), allOnes);
    };
    for (size_t chunk = 0; chunk + 4 <= n; chunk += kChunk) {
      const size_t end = std::min(n - n % 4, chunk + kChunk);
      start = end;
      size_t count = 0;
      for (size_t c = chunk; c < end; c += 4) {
        const F4 active = activeMask(_mm_loadu_ps(cloudW + c), _mm_loadu_ps(rainW + c), columnAt(c).threshold);
        _mm_storeu_ps(rateOut + c, zero);
        blockOf[count] = uint32_t(c);
        count += _mm_movemask_ps(active) != 0;
      }
      for (size_t k = 0; k < count; ++k) {
        const size_t c = blockOf[k];
        saturatedOf[k] = _mm_mul_ps(
            set1(rhoH), saturationMixingRatioFast4(_mm_add_ps(set1(tRef), _mm_loadu_ps(anomalyT + c)), set1(p0)));
        // Accretion's (r_r)^0.875 and the share of the rain that falls out in the step.
        const Column column = columnAt(c);
        accretionOf[k] = powFast(_mm_div_ps(_mm_loadu_ps(rainW + c), _mm_mul_ps(rhoV, column.depth)), 0.875f);
        const F4 midHeight = maxStd(_mm_mul_ps(set1(0.5f), _mm_add_ps(column.base, column.top)), set1(500.0f));
        fallShareOf[k] = oneMinusExpFast(_mm_div_ps(set1(dt * kFallSpeed), midHeight));
      }
      // What converts, and the share of the falling rain that evaporates below the base.
      for (size_t k = 0; k < count; ++k) {
        const size_t c = blockOf[k];
        const F4 cloud = _mm_loadu_ps(cloudW + c);
        const Column column = columnAt(c);
        const F4 base = column.base, threshold = column.threshold;
        const F4 rate = _mm_add_ps(_mm_mul_ps(set1(kAutoconversionRate), maxStd(zero, _mm_sub_ps(cloud, threshold))),
                                   _mm_mul_ps(_mm_mul_ps(set1(2.2f), cloud), accretionOf[k]));
        const F4 converts = _mm_and_ps(_mm_cmpgt_ps(cloud, zero), _mm_cmpgt_ps(rate, zero));
        convertedOf[k] =
            _mm_and_ps(converts, _mm_mul_ps(cloud, oneMinusExpFast(_mm_div_ps(_mm_mul_ps(rate, set1(dt)), cloud))));
        const F4 saturated = saturatedOf[k];
        const F4 humidity =
            select(_mm_cmpgt_ps(saturated, zero),
                   clampStd(_mm_div_ps(_mm_loadu_ps(vapourW + c), saturated), zero, set1(1.0f)), set1(1.0f));
        evaporatingShareOf[k] =
            minStd(set1(0.9f),
                   _mm_mul_ps(_mm_mul_ps(_mm_mul_ps(set1(0.5f), _mm_sub_ps(set1(1.0f), humidity)), base), set1(1e-3f)));
      }
      for (size_t k = 0; k < count; ++k) {
        const size_t c = blockOf[k];
        F4 cloud = _mm_loadu_ps(cloudW + c), rain = _mm_loadu_ps(rainW + c);
        const F4 active = activeMask(cloud, rain, columnAt(c).threshold);
        // Cloud → rain (the amount from above; 0: no move).
        F4 newCloud = cloud, rainNow = rain;
        transferWater(newCloud, rainNow, convertedOf[k]);
        // Rain-out, part evaporating below the base.
        const F4 fallen = _mm_mul_ps(rainNow, fallShareOf[k]);
        const F4 vapour = _mm_loadu_ps(vapourW + c), anomaly = _mm_loadu_ps(anomalyT + c);
        const F4 share = evaporatingShareOf[k];
        F4 evaporated = _mm_mul_ps(fallen, share);
        const F4 newRain = _mm_sub_ps(rainNow, fallen);
        F4 newVapour = _mm_add_ps(vapour, evaporated);
        // A trace below the vapour path's resolution cannot evaporate exactly: the rounded gain could
        // exceed what the rain lost (a negative rate at the ground); it falls out instead (both
        // differences are exact in double).
        const __m128d lostA = _mm_sub_pd(_mm_cvtps_pd(rainNow), _mm_cvtps_pd(newRain));
        const __m128d lostB =
            _mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(rainNow, rainNow)), _mm_cvtps_pd(_mm_movehl_ps(newRain, newRain)));
        const __m128d gainA = _mm_sub_pd(_mm_cvtps_pd(newVapour), _mm_cvtps_pd(vapour));
        const __m128d gainB =
            _mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(newVapour, newVapour)), _mm_cvtps_pd(_mm_movehl_ps(vapour, vapour)));
        const F4 inexact = _mm_shuffle_ps(_mm_castpd_ps(_mm_cmpgt_pd(gainA, lostA)),
                                          _mm_castpd_ps(_mm_cmpgt_pd(gainB, lostB)), _MM_SHUFFLE(2, 0, 2, 0));
        evaporated = _mm_andnot_ps(inexact, evaporated);
        newVapour = select(inexact, vapour, newVapour);
        // What left the fields is exactly what the stored values lost (round-off included), in double.
        const __m128d leftA = _mm_sub_pd(lostA, _mm_and_pd(_mm_cmple_pd(gainA, lostA), gainA));
        const __m128d leftB = _mm_sub_pd(lostB, _mm_and_pd(_mm_cmple_pd(gainB, lostB), gainB));
        const F4 precipitation =
            _mm_movelh_ps(_mm_cvtpd_ps(_mm_div_pd(leftA, dtPair)), _mm_cvtpd_ps(_mm_div_pd(leftB, dtPair)));
        // Lanes without work keep everything (their update would change nothing: see the scalar pass).
        const __m128d activeLo = _mm_castps_pd(_mm_unpacklo_ps(active, active));
        const __m128d activeHi = _mm_castps_pd(_mm_unpackhi_ps(active, active));
        leftLo = _mm_add_pd(leftLo, _mm_and_pd(activeLo, leftA));
        leftHi = _mm_add_pd(leftHi, _mm_and_pd(activeHi, leftB));
        _mm_storeu_ps(cloudW + c, select(active, newCloud, cloud));
        _mm_storeu_ps(rainW + c, select(active, newRain, rain));
        _mm_storeu_ps(vapourW + c, select(active, newVapour, vapour));
        _mm_storeu_ps(anomalyT + c,
                      select(active, _mm_sub_ps(anomaly, _mm_mul_ps(set1(kelvinPerKg), evaporated)), anomaly));
        _mm_storeu_ps(rateOut + c, _mm_and_ps(active, precipitation));
      }
    }
    alignas(16) double parts[4];
    _mm_store_pd(parts, leftLo);
    _mm_store_pd(parts + 2, leftHi);
    out = (parts[0] + parts[1]) + (parts[2] + parts[3]);
  }
#endif
  // The remaining cells (all of them without SSE2): which have work, then the update of those. A column
  // without rain whose cloud is below the autoconversion threshold converts nothing (accretion needs
  // rain) and drops nothing, so the full update would leave it as it is.
  const float thresholdPerMetre = rho * kThresholdMixingRatio;
  work.active.assign(n - start, 0);
  for (size_t c = start; c < n; ++c) {
    const float cloud = s.cloudWater[c], rain = s.rain[c], base = s.cloudBase[c];
    const float top = std::max(s.cloudTop[c], base + 100.0f);
    const float threshold = thresholdPerMetre * std::min(top - base, 2000.0f);
    const bool empty = cloud <= 0.0f && rain <= 0.0f;
    const bool idle = rain == 0.0f && cloud <= threshold;
    work.active[c - start] = uint8_t(!(empty || idle));
    s.precipitationRate[c] = 0.0f;
  }
  forEachActiveCell(work.active, [&](size_t k) {
    const size_t c = start + k;
    float cloud = s.cloudWater[c], rain = s.rain[c];
    float base = s.cloudBase[c], top = std::max(s.cloudTop[c], base + 100.0f);
    float depth = top - base;
    // Cloud → rain.
    if (cloud > 0.0f) {
      float threshold = rho * kThresholdMixingRatio * std::min(depth, 2000.0f);
      float rainMixing = rain / (rho * depth);
      float rate = kAutoconversionRate * std::max(0.0f, cloud - threshold) + 2.2f * cloud * powFast(rainMixing, 0.875f);
      if (rate > 0.0f) {
        float converted = cloud * oneMinusExpFast(rate * dt / cloud);
        transferWater(s.cloudWater[c], rain, converted);
      }
    }
    // Rain-out, part evaporating below the base.
    float midHeight = std::max(0.5f * (base + top), 500.0f);
    float fallen = rain * oneMinusExpFast(dt * kFallSpeed / midHeight);
    float vapour = s.vapour[c];
    float saturated = rhoH * saturationMixingRatioFast(tRef + s.temperature[c], p0);
    float humidity = saturated > 0.0f ? std::clamp(vapour / saturated, 0.0f, 1.0f) : 1.0f;
    float evaporatedShare = std::min(0.9f, 0.5f * (1.0f - humidity) * base * 1e-3f);
    float evaporated = fallen * evaporatedShare;
    float newRain = rain - fallen;
    float newVapour = vapour + evaporated;
    // A trace below the vapour path's resolution cannot evaporate exactly: the rounded gain could exceed
    // what the rain lost (a negative rate at the ground); it falls out instead.
    if (double(newVapour) - double(vapour) > double(rain) - double(newRain)) {
      newVapour = vapour;
      evaporated = 0.0f;
    }
    // What left the fields is exactly what the stored values lost (round-off included).
    double left = (double(rain) - double(newRain)) - (double(newVapour) - double(vapour));
    s.rain[c] = newRain;
    s.vapour[c] = newVapour;
    s.temperature[c] -= kelvinPerKg * evaporated;
    s.precipitationRate[c] = float(left / dt_s);
    out += left;
  });
  return out * s.cellArea();
}

}  // namespace firmament::weather
