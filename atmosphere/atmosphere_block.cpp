#include "atmosphere/atmosphere_block.h"

namespace firmament {
namespace {

void put3(float (&out)[4], const glm::dvec3& v, double w = 0.0) {
  out[0] = float(v.x);
  out[1] = float(v.y);
  out[2] = float(v.z);
  out[3] = float(w);
}

void putLayer(float* flat, int first, const shared::DensityLayer& layer) {
  flat[first + 0] = float(layer.width);
  flat[first + 1] = float(layer.exp_term);
  flat[first + 2] = float(layer.exp_scale);
  flat[first + 3] = float(layer.linear_term);
  flat[first + 4] = float(layer.constant_term);
}

}  // namespace

AtmosphereBlock packAtmosphereBlock(const shared::AtmosphereParameters& a, const glm::dmat3& sky, const glm::dmat3& sun) {
  AtmosphereBlock b{};
  b.radii[0] = float(a.bottom_radius);
  b.radii[1] = float(a.top_radius);
  b.radii[2] = float(a.sun_angular_radius);
  b.radii[3] = float(a.mie_phase_g);
  put3(b.solarIrradiance, a.solar_irradiance, a.mu_s_min);
  put3(b.rayleighScattering, a.rayleigh_scattering);
  put3(b.mieScattering, a.mie_scattering);
  put3(b.mieExtinction, a.mie_extinction);
  put3(b.absorptionExtinction, a.absorption_extinction);
  put3(b.groundAlbedo, a.ground_albedo);
  float* flat = &b.profiles[0][0];
  putLayer(flat, 0, a.rayleigh_density.layer0);
  putLayer(flat, 5, a.rayleigh_density.layer1);
  putLayer(flat, 10, a.mie_density.layer0);
  putLayer(flat, 15, a.mie_density.layer1);
  putLayer(flat, 20, a.absorption_density.layer0);
  putLayer(flat, 25, a.absorption_density.layer1);
  for (int c = 0; c < 3; ++c) {
    put3(b.skyRadianceToRgb[c], sky[c]);
    put3(b.sunRadianceToRgb[c], sun[c]);
  }
  return b;
}

}  // namespace firmament
