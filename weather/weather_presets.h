#pragma once
// Weather regimes as sets of air-mass parameters. A preset does not paint clouds: it sets the sounding
// (temperature profile), moisture, radiation and large-scale lifting, and the model makes the clouds.
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace firmament::weather {

struct PresetParameters {
  double referenceTemperature_K = 293.0;  // air-mass surface temperature (the anomaly's zero)
  double boundaryLayerDepth_m = 1000.0;   // h₀: the mixed layer's depth before sunrise (it grows by day)
  double relativeHumidity = 0.6;          // background boundary-layer relative humidity
  double inversion_K = 1.5;               // capping-inversion jump at h
  double lapseRate_K_per_km = 6.5;        // free troposphere from h to the stable layer
  double stableLayerBase_m = 11000.0;     // a subsidence/trade inversion (fair weather) or the tropopause
  double upperLapseRate_K_per_km = 6.5;   // from the stable layer to the tropopause
  double tropopause_m = 11000.0;          // isothermal above
  double freeTroposphereRH = 0.5;         // relative humidity cloud edges mix with (detrainment)
  double absorbedSolar_W_m2 = 650.0;      // net shortwave at the ground, zenith sun, clear sky
  double bowenRatio = 0.6;                // sensible / latent heat flux
  double largeScaleLift_m_s = 0.0;        // uniform synoptic ascent (stratus, overcast)
  double frontLift_m_s = 0.0;             // extra ascent in a band moving with the wind (fronts)
  double frontWidth_m = 15000.0;          // e-folding half width of that band

  // Parameters as a flat list, so that transitions blend every field the same way.
  static constexpr int kCount = 14;
  std::array<double, kCount> toArray() const;
  static PresetParameters fromArray(const std::array<double, kCount>& values);
};

// The named regimes: clear, fair-weather, scattered-showers, thunderstorm, overcast, frontal.
const std::vector<std::string>& presetNames();
bool isPresetName(std::string_view name);
// Throws InputError naming the allowed values for an unknown name.
PresetParameters presetParameters(std::string_view name);

// Linear blend a + s (b − a), field by field.
PresetParameters blend(const PresetParameters& a, const PresetParameters& b, double s);

}  // namespace firmament::weather
