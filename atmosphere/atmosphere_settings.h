#pragma once
// The physical description of a clear-sky atmosphere, independent of wavelength sampling, and its
// evaluation at three wavelengths into the shared AtmosphereParameters (common/atmosphere_medium.glsl).
// Defaults are Bruneton 2017's Earth (docs/atmosphere.md lists each value and its source).
#include <glm/glm.hpp>
#include <string>

#include "common/atmosphere_medium.glsl"
#include "core/scene.h"

namespace firmament {

struct AtmosphereSettings {
  double bottomRadius = 6360e3;               // m, sea level
  double topRadius = 6420e3;                  // m
  double groundHeight = 0.0;                  // m above sea level of the ground sphere (the scene's location)
  double rayleighScaleHeight = 8000.0;        // m
  double rayleighScatteringUm4 = 1.24062e-6;  // m^-1 µm^4: beta_R(lambda) = k lambda^-4
  double mieAngstromAlpha = 0.0;
  double mieAngstromBeta = 5.328e-3;  // aerosol optical depth at 1 µm
  double mieScaleHeight = 1200.0;     // m
  double mieSingleScatteringAlbedo = 0.9;
  double miePhaseG = 0.8;
  double ozoneColumnDobson = 300.0;  // DU
  double groundAlbedo = 0.1;
  double sunAngularRadius = 0.00935 / 2.0;  // rad
  // The solar spectrum is tabulated at 1 au; the irradiance falls as 1/d^2 with the Earth-Sun distance
  // d (au), from 0.967 in early January to 1.034 in early July. 1 = the mean distance.
  double solarIrradianceScale = 1.0;
  // Largest sun zenith angle the scattering tables represent; a lower sun reads the value at this
  // angle. 108 degrees is the end of astronomical twilight: the sunlit sky is then ~1e-5 cd/m^2,
  // below the natural night sky (~2e-4 cd/m^2), so the clamp is invisible. Bruneton 2017 uses 102
  // degrees, which leaves a visible plateau of ~0.01-0.1 cd/m^2 through nautical and astronomical
  // twilight (docs/atmosphere-tables.md).
  double muSMin = -0.30901699437494734;  // cos(108 deg)

  static AtmosphereSettings fromScene(const Scene& scene);
  // 16 hex digits identifying every field, for caching tables.
  std::string hash() const;
};

// Evaluates the medium at three wavelengths (nm). The ground sphere is at bottomRadius +
// groundHeight; density profiles are shifted so that densities stay those of the true altitude above
// sea level (an exponential shifted by h0 is still an exponential, scaled by exp(-h0/H)).
shared::AtmosphereParameters atmosphereParametersAt(const AtmosphereSettings& settings, glm::dvec3 wavelengthsNm);

// Physical constants used above (Bruneton 2017, demo/model; Dobson unit definition).
inline constexpr double kDobsonUnit = 2.687e20;         // molecules m^-2
inline constexpr double kOzoneTentHalfWidth = 15000.0;  // m: tent from 10 to 40 km, peak at 25 km
inline constexpr double kOzoneTentBottom = 10000.0;     // m above sea level
inline constexpr double kOzoneTentPeak = 25000.0;       // m above sea level

}  // namespace firmament
