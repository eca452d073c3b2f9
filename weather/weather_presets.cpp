#include "weather/weather_presets.h"

#include "core/error.h"

namespace firmament::weather {

std::array<double, PresetParameters::kCount> PresetParameters::toArray() const {
  return {referenceTemperature_K,
          boundaryLayerDepth_m,
          relativeHumidity,
          inversion_K,
          lapseRate_K_per_km,
          stableLayerBase_m,
          upperLapseRate_K_per_km,
          tropopause_m,
          freeTroposphereRH,
          absorbedSolar_W_m2,
          bowenRatio,
          largeScaleLift_m_s,
          frontLift_m_s,
          frontWidth_m};
}

PresetParameters PresetParameters::fromArray(const std::array<double, kCount>& v) {
  PresetParameters p;
  p.referenceTemperature_K = v[0];
  p.boundaryLayerDepth_m = v[1];
  p.relativeHumidity = v[2];
  p.inversion_K = v[3];
  p.lapseRate_K_per_km = v[4];
  p.stableLayerBase_m = v[5];
  p.upperLapseRate_K_per_km = v[6];
  p.tropopause_m = v[7];
  p.freeTroposphereRH = v[8];
  p.absorbedSolar_W_m2 = v[9];
  p.bowenRatio = v[10];
  p.largeScaleLift_m_s = v[11];
  p.frontLift_m_s = v[12];
  p.frontWidth_m = v[13];
  return p;
}

const std::vector<std::string>& presetNames() {
  static const std::vector<std::string> names = {"clear",        "fair-weather", "scattered-showers",
                                                 "thunderstorm", "overcast",     "frontal"};
  return names;
}

bool isPresetName(std::string_view name) {
  for (const auto& n : presetNames())
    if (n == name) return true;
  return false;
}

// Soundings are typical mid-latitude summer cases (cf. Stull 1988 ch. 1 and Markowski & Richardson 2010
// ch. 7 for shallow-cumulus and deep-convection environments); the numbers are choices, not fits.
PresetParameters presetParameters(std::string_view name) {
  PresetParameters p;
  if (name == "clear") {
    // Dry air under strong subsidence: the thermals never reach saturation.
    p.relativeHumidity = 0.35;
    p.inversion_K = 4.0;
    p.lapseRate_K_per_km = 5.0;
    p.freeTroposphereRH = 0.2;
  } else if (name == "fair-weather") {
    // Shallow cumulus capped by a subsidence inversion near 2.5 km; the morning layer of 600 m grows to
    // ≈ 1.2 km, where its thermals reach their condensation level.
    p.boundaryLayerDepth_m = 600.0;
    p.relativeHumidity = 0.6;
    p.inversion_K = 1.0;
    p.lapseRate_K_per_km = 6.5;
    p.stableLayerBase_m = 2600.0;
    p.upperLapseRate_K_per_km = 1.0;
    p.freeTroposphereRH = 0.45;
  } else if (name == "scattered-showers") {
    // Congestus that rains: a deeper moist layer, stable layer at 6 km.
    p.referenceTemperature_K = 291.0;
    p.boundaryLayerDepth_m = 700.0;
    p.relativeHumidity = 0.65;
    p.inversion_K = 0.5;
    p.lapseRate_K_per_km = 7.0;
    p.stableLayerBase_m = 6000.0;
    p.upperLapseRate_K_per_km = 3.0;
    p.freeTroposphereRH = 0.7;
  } else if (name == "thunderstorm") {
    // Warm, moist, conditionally unstable to the tropopause; a 1.5 K cap that only the strongest heating
    // or a gust front breaks, so storms start in places, not everywhere.
    p.referenceTemperature_K = 298.0;
    p.boundaryLayerDepth_m = 800.0;
    p.relativeHumidity = 0.6;
    p.inversion_K = 1.5;
    p.lapseRate_K_per_km = 7.0;
    p.stableLayerBase_m = 12000.0;
    p.upperLapseRate_K_per_km = 7.0;
    p.tropopause_m = 12000.0;
    p.freeTroposphereRH = 0.6;
  } else if (name == "overcast") {
    // A moist layer under a strong inversion, slow ascent: a stratus deck.
    p.referenceTemperature_K = 287.0;
    p.boundaryLayerDepth_m = 900.0;
    p.relativeHumidity = 0.93;
    p.inversion_K = 6.0;
    p.lapseRate_K_per_km = 5.5;
    p.freeTroposphereRH = 0.8;
    p.absorbedSolar_W_m2 = 350.0;
    p.largeScaleLift_m_s = 0.01;
  } else if (name == "frontal") {
    // Broad synoptic ascent plus a frontal band: nimbostratus that rains.
    p.referenceTemperature_K = 290.0;
    p.relativeHumidity = 0.85;
    p.inversion_K = 1.5;
    p.lapseRate_K_per_km = 6.0;
    p.freeTroposphereRH = 0.85;
    p.absorbedSolar_W_m2 = 400.0;
    p.largeScaleLift_m_s = 0.01;
    p.frontLift_m_s = 0.08;
  } else {
    std::string allowed;
    for (const auto& n : presetNames()) allowed += (allowed.empty() ? "" : ", ") + n;
    throw InputError("unknown weather preset '" + std::string(name) + "' (allowed: " + allowed + ")");
  }
  return p;
}

PresetParameters blend(const PresetParameters& a, const PresetParameters& b, double s) {
  auto va = a.toArray(), vb = b.toArray();
  for (int i = 0; i < PresetParameters::kCount; ++i) va[i] += s * (vb[i] - va[i]);
  return PresetParameters::fromArray(va);
}

}  // namespace firmament::weather
