#include "weather/stratiform.h"

#include <algorithm>
#include <cmath>

#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {

void applyStratiform(WeatherState& s, const BoundaryLayer& layer, const StratiformParameters& p, double dt_s) {
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
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      size_t c = s.index(i, j);
      // Large-scale ascent, with the frontal band at periodic distance d along the front's motion.
      float lift = float(p.largeScaleLift_m_s);
      if (lifting) {
        if (p.frontLift_m_s != 0.0 && period > 0.0) {
          double along = ((i + 0.5) * p.frontDirectionX + (j + 0.5) * p.frontDirectionY) * s.cellSize_m;
          double d = std::remainder(along - p.frontPosition_m, period);
          lift += float(p.frontLift_m_s * std::exp(-(d * d) / (p.frontWidth_m * p.frontWidth_m)));
        }
        s.lift[c] += lift;
        s.temperature[c] -= float(kDryAdiabaticLapseRate) * lift * float(dt_s);
      }

      float topTemperature = float(layer.referenceTemperature_K) + s.temperature[c] - topCooling;
      float saturated = rhoH * saturationMixingRatioFast(topTemperature, topPressure);
      float vapour = s.vapour[c], cloud = s.cloudWater[c], conv = s.convectiveFraction[c];
      if (vapour > saturated) {
        float dq = (vapour - saturated) * condense;
        transferWater(s.vapour[c], s.cloudWater[c], dq);
        s.temperature[c] += kelvinPerKg * dq;
        // The new water is stratiform: the convective share drops by mass weighting.
        s.convectiveFraction[c] = cloud + dq > 0.0f ? conv * cloud / (cloud + dq) : 0.0f;
        float stratiformTop = depth + std::min(8000.0f, std::max(lift, 0.0f) * 1e5f);
        if (conv < 0.5f || s.cloudTop[c] < stratiformTop) s.cloudTop[c] = std::max(s.cloudTop[c] * conv, stratiformTop);
      } else if (cloud > 0.0f) {
        float layerDeficit = saturated > 0.0f ? std::clamp(1.0f - vapour / saturated, 0.0f, 1.0f) : 1.0f;
        float e = cloud * evaporate * (conv * ftDeficit + (1.0f - conv) * layerDeficit);
        transferWater(s.cloudWater[c], s.vapour[c], e);
        s.temperature[c] -= (1.0f - conv) * kelvinPerKg * e;
      }
    }
  }
}

}  // namespace firmament::weather
