#include "atmosphere/atmosphere_settings.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "atmosphere/atmosphere_spectra.h"
#include "core/hash.h"

namespace firmament {

AtmosphereSettings AtmosphereSettings::fromScene(const Scene& scene) {
  AtmosphereSettings s;
  s.bottomRadius = scene.number("/atmosphere/bottom_radius_m");
  s.topRadius = s.bottomRadius + scene.number("/atmosphere/thickness_m");
  s.groundHeight = scene.number("/location/height_m");
  s.rayleighScaleHeight = scene.number("/atmosphere/rayleigh_scale_height_m");
  s.rayleighScatteringUm4 = scene.number("/atmosphere/rayleigh_scattering_um4");
  s.mieAngstromAlpha = scene.number("/atmosphere/mie/angstrom_alpha");
  s.mieAngstromBeta = scene.number("/atmosphere/mie/angstrom_beta");
  s.mieScaleHeight = scene.number("/atmosphere/mie/scale_height_m");
  s.mieSingleScatteringAlbedo = scene.number("/atmosphere/mie/single_scattering_albedo");
  s.miePhaseG = scene.number("/atmosphere/mie/phase_g");
  s.ozoneColumnDobson = scene.number("/atmosphere/ozone/column_dobson");
  s.groundAlbedo = scene.number("/atmosphere/ground_albedo");
  s.sunAngularRadius = scene.number("/atmosphere/sun_angular_radius_deg") * 3.14159265358979323846 / 180.0;
  return s;
}

std::string AtmosphereSettings::hash() const {
  const double fields[] = {bottomRadius,
                           topRadius,
                           groundHeight,
                           rayleighScaleHeight,
                           rayleighScatteringUm4,
                           mieAngstromAlpha,
                           mieAngstromBeta,
                           mieScaleHeight,
                           mieSingleScatteringAlbedo,
                           miePhaseG,
                           ozoneColumnDobson,
                           groundAlbedo,
                           sunAngularRadius,
                           muSMin,
                           solarIrradianceScale};
  // FNV-1a over the bytes of every field: any change of any parameter changes the key.
  return hex16(fnv1a(std::string_view(reinterpret_cast<const char*>(fields), sizeof(fields))));
}

namespace {

// Exponential profile exp(-(h + h0)/H) for altitude h above the ground sphere at height h0.
shared::DensityProfile exponentialProfile(double scaleHeight, double groundHeight) {
  shared::DensityProfile p{};
  p.layer0 = {0.0, std::exp(-groundHeight / scaleHeight), -1.0 / scaleHeight, 0.0, 0.0};
  p.layer1 = p.layer0;
  return p;
}

// Ozone tent in true altitude a = h + h0: rising linearly from 10 km to 1 at 25 km, falling to 0 at
// 40 km (Bruneton 2017's Earth): d = a/15km - 2/3 below 25 km, d = -a/15km + 8/3 above.
shared::DensityProfile ozoneProfile(double groundHeight) {
  const double slope = 1.0 / kOzoneTentHalfWidth;
  shared::DensityProfile p{};
  p.layer0 = {kOzoneTentPeak - groundHeight, 0.0, 0.0, slope, slope * groundHeight - kOzoneTentBottom * slope};
  p.layer1 = {0.0, 0.0, 0.0, -slope, -slope * groundHeight + (kOzoneTentPeak + kOzoneTentHalfWidth) * slope};
  return p;
}

}  // namespace

shared::AtmosphereParameters atmosphereParametersAt(const AtmosphereSettings& s, glm::dvec3 wavelengthsNm) {
  shared::AtmosphereParameters a{};
  a.bottom_radius = s.bottomRadius + s.groundHeight;
  a.top_radius = s.topRadius;
  a.sun_angular_radius = s.sunAngularRadius;
  a.mie_phase_g = s.miePhaseG;
  a.mu_s_min = s.muSMin;
  // Peak ozone number density so the tent's column (peak * 15 km) equals the Dobson column.
  const double ozonePeakDensity = s.ozoneColumnDobson * kDobsonUnit / kOzoneTentHalfWidth;  // m^-3
  for (int i = 0; i < 3; ++i) {
    double lambda = wavelengthsNm[i];
    double lambdaUm = lambda * 1e-3;
    a.solar_irradiance[i] = solarIrradiance(lambda) * s.solarIrradianceScale;
    a.rayleigh_scattering[i] = s.rayleighScatteringUm4 * std::pow(lambdaUm, -4.0);
    // Angstrom: aerosol optical depth tau(lambda) = beta lambda^-alpha (lambda in µm); spread over an
    // exponential profile of scale height H the extinction at density 1 is tau / H.
    double mieExtinction = s.mieAngstromBeta / s.mieScaleHeight * std::pow(lambdaUm, -s.mieAngstromAlpha);
    a.mie_extinction[i] = mieExtinction;
    a.mie_scattering[i] = mieExtinction * s.mieSingleScatteringAlbedo;
    a.absorption_extinction[i] = ozonePeakDensity * ozoneCrossSection(lambda);
    a.ground_albedo[i] = s.groundAlbedo;
  }
  a.rayleigh_density = exponentialProfile(s.rayleighScaleHeight, s.groundHeight);
  a.mie_density = exponentialProfile(s.mieScaleHeight, s.groundHeight);
  a.absorption_density = ozoneProfile(s.groundHeight);
  return a;
}

}  // namespace firmament
