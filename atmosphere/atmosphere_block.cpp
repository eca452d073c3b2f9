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

// Legendre moments a_l = 2 pi ∫_-1^1 p(mu) P_l(mu) dmu, l = 1, 2, of the aerosol's Cornette-Shanks
// phase (shared with the shaders), by the midpoint rule on 4096 intervals (the forward peak of g = 0.8 is
// ~10 degrees wide: converged to ~1e-6). They weight the anisotropy of multiple scattering
// (atmosphere/multiple_scattering_lut.glsl).
glm::dvec2 miePhaseMoments(double g) {
  constexpr int kIntervals = 4096;
  glm::dvec2 sum(0.0);
  for (int i = 0; i < kIntervals; ++i) {
    const double mu = -1.0 + 2.0 * (i + 0.5) / kIntervals;
    const double p = shared::cornetteShanksPhase(g, mu);
    sum += p * glm::dvec2(mu, 0.5 * (3.0 * mu * mu - 1.0));
  }
  return sum * (2.0 * 3.14159265358979323846 * 2.0 / kIntervals);
}

}  // namespace

AtmosphereBlock packAtmosphereBlock(const shared::AtmosphereParameters& a, const glm::dmat3& sky,
                                    const glm::dmat3& sun) {
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
  const glm::dvec2 moments = miePhaseMoments(a.mie_phase_g);
  flat[30] = float(moments.x);
  flat[31] = float(moments.y);
  for (int c = 0; c < 3; ++c) {
    put3(b.skyRadianceToRgb[c], sky[c]);
    put3(b.sunRadianceToRgb[c], sun[c]);
  }
  return b;
}

}  // namespace firmament
