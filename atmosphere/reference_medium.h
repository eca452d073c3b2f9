#pragma once
// The clear-sky medium at N wavelengths, for the CPU reference (docs/reference.md, "Medium").
//
// Every coefficient comes from the shared medium (common/atmosphere_medium.glsl, compiled as C++
// double): the settings are evaluated three wavelengths at a time by atmosphereParametersAt, and
// the per-wavelength numbers are read back out of those AtmosphereParameters. Nothing is re-derived.
//
// The extinction is a sum of three constituents, each a wavelength-dependent coefficient times a
// wavelength-independent density profile (atmosphere_medium.glsl):
//   sigma_t(lambda, r) = beta_R(lambda) d_R(r) + beta_M^e(lambda) d_M(r) + beta_O(lambda) d_O(r).
// So one integral of the density vector D = ∫ (d_R, d_M, d_O) ds along a segment gives the optical
// depth at every wavelength: tau(lambda) = beta_R D_R + beta_M^e D_M + beta_O D_O. The reference
// integrates D once and serves all N wavelengths from it. The density vector itself is evaluated
// by the shared extinctionAt() on a "probe" parameter set whose three channels are the unit
// coefficients of the three constituents, so the profiles, their clamping and the empty space above
// the top radius are exactly the shared code's.
#include <glm/glm.hpp>
#include <vector>

#include "atmosphere/atmosphere_settings.h"
#include "common/atmosphere_medium.glsl"

namespace firmament::reference {

// Densities (dimensionless, in [0, 1]) of Rayleigh, Mie and ozone at one point, in that order.
using ConstituentDensities = glm::dvec3;

class SpectralMedium {
 public:
  // From scene settings at the given wavelengths (nm, any count >= 1).
  static SpectralMedium fromSettings(const AtmosphereSettings& settings, const std::vector<double>& wavelengthsNm);
  // From shared parameter sets, one per consecutive triple of wavelengths (the last triple may be
  // padded: only the first wavelengthsNm.size() channels are used). Geometry, phase asymmetry and
  // density profiles must agree between the triples (they do not depend on wavelength). Lets tests
  // build media the scene format cannot describe (constant density, no ozone, ...).
  static SpectralMedium fromParameters(const std::vector<shared::AtmosphereParameters>& triples,
                                       const std::vector<double>& wavelengthsNm);

  int wavelengthCount() const { return int(wavelengths_.size()); }
  const std::vector<double>& wavelengths() const { return wavelengths_; }

  // Wavelength-independent geometry and phase (m, rad, 1).
  double groundRadius() const { return geometry_.bottom_radius; }
  double topRadius() const { return geometry_.top_radius; }
  double sunAngularRadius() const { return geometry_.sun_angular_radius; }
  double miePhaseG() const { return geometry_.mie_phase_g; }
  // The first triple's shared parameters: geometry for the shared ray functions (atmosphere_lut.glsl).
  const shared::AtmosphereParameters& geometry() const { return geometry_; }

  // (d_R, d_M, d_O) at radius r (m), through shared::extinctionAt on the probe (zero above the top).
  ConstituentDensities densitiesAt(double r) const { return shared::extinctionAt(probe_, r); }

  // Per-wavelength coefficients at density 1 (m^-1) and the solar irradiance (W m^-2 nm^-1) and
  // ground albedo (1), index = wavelength index.
  double rayleighScattering(int i) const { return rayleighScattering_[i]; }
  double mieScattering(int i) const { return mieScattering_[i]; }
  double mieExtinction(int i) const { return mieExtinction_[i]; }
  double ozoneAbsorption(int i) const { return ozoneAbsorption_[i]; }
  double solarIrradiance(int i) const { return solarIrradiance_[i]; }
  double groundAlbedo(int i) const { return groundAlbedo_[i]; }
  // Extinction per unit density of each constituent: (beta_R, beta_M^e, beta_O), so that
  // sigma_t = dot(extinctionPerDensity(i), densities) and tau = dot(extinctionPerDensity(i), D).
  glm::dvec3 extinctionPerDensity(int i) const {
    return {rayleighScattering_[i], mieExtinction_[i], ozoneAbsorption_[i]};
  }
  // The largest of each constituent's coefficient over the wavelengths (m^-1): the scale on which
  // the quadrature measures the error of a density integral.
  glm::dvec3 maxExtinctionPerDensity() const { return maxExtinctionPerDensity_; }

  // Radii (m, sorted, strictly between ground and top) where a density profile has a kink or a
  // jump: a layer boundary, or where a linear or exponential layer is clamped at 0 or 1. Quadrature
  // panels start and end there, so that every panel integrates a smooth function (a kink inside a
  // panel makes the error estimate converge only as h^2, and the adaptive bisection dig deep).
  // At most kMaxDensityBreaks of them.
  static constexpr int kMaxDensityBreaks = 15;
  const std::vector<double>& densityBreakRadii() const { return densityBreakRadii_; }

 private:
  std::vector<double> wavelengths_;
  shared::AtmosphereParameters geometry_{};
  shared::AtmosphereParameters probe_{};
  std::vector<double> rayleighScattering_, mieScattering_, mieExtinction_, ozoneAbsorption_;
  std::vector<double> solarIrradiance_, groundAlbedo_;
  glm::dvec3 maxExtinctionPerDensity_{0.0};
  std::vector<double> densityBreakRadii_;
};

// N wavelengths evenly spaced over [360, 830] nm (N = 48 gives the solar table's 10 nm grid); N = 1
// gives 555 nm.
std::vector<double> evenlySpacedWavelengths(int count);

}  // namespace firmament::reference
