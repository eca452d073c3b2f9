#pragma once
// The deterministic part of the reference (docs/reference.md): orders 0 and 1 along one view ray,
// by adaptive quadrature in double.
//
//   order 0 (sun disc, only for rays inside it and not blocked by the ground):
//     L_0(lambda) = T(lambda; 0, D) L_disc(lambda, theta)
//   order 1 (single scattering of the sun, a point source for in-scattering, as in the fast path):
//     L_1(lambda) = ∫_0^D T(lambda; 0, t) [ sigma_R(lambda, t) p_R(nu) + sigma_M(lambda, t) p_CS(g, nu) ]
//                         E(lambda) T_sun(lambda, x_t) V(x_t) dt
//                 + [ray meets the ground] T(lambda; 0, D) a(lambda)/pi E(lambda) max(mu_s, 0) T_sun(lambda, x_D)
// with T the transmittance exp(-tau), D the length of the view segment, nu = cos(view, sun) constant
// along the ray (the sun is at infinity), V the planet's shadow by geometry and T_sun the
// transmittance from x_t to the top toward the sun, itself an adaptive quadrature
// (ColumnIntegrator::columnToSun).
#include <glm/glm.hpp>
#include <vector>

#include "atmosphere/reference_geometry.h"
#include "atmosphere/reference_optical_depth.h"

namespace firmament::reference {

// Limb darkening I(mu)/I(1) = mu^kLimbDarkeningExponent (a power law, as the fast path uses).
inline constexpr double kLimbDarkeningExponent = 0.5;

// The sun disc's radiance profile: L_disc(lambda, theta) = E(lambda) mu(theta)^0.5 / Omega_eff with
// mu = sqrt(1 - (sin theta / sin alpha)^2) (the cosine on the solar surface of the point seen at
// angle theta from the disc centre; alpha = angular radius) and Omega_eff = ∫_disc mu^0.5 dOmega, so
// that ∫_disc L_disc dOmega = E exactly.
class SunDisc {
 public:
  explicit SunDisc(double angularRadius);
  // mu^0.5 / Omega_eff (sr^-1) for a direction at cosine cosTheta from the disc centre; 0 outside.
  double profile(double cosTheta, double sinTheta) const;
  double effectiveSolidAngle() const { return effectiveSolidAngle_; }
  double angularRadius() const { return angularRadius_; }

 private:
  double angularRadius_;
  double cosRadius_;
  double sinRadius_;
  double effectiveSolidAngle_;
};

struct DeterministicRadiance {
  std::vector<double> sunDisc;           // W m^-2 sr^-1 nm^-1 per wavelength
  std::vector<double> singleScattering;  // medium and ground
  ConstituentDensities viewColumn{0.0};  // D along the whole view segment (m)
};

class SingleScatteringIntegrator {
 public:
  // relativeTolerance: per panel and per wavelength, |K15 - G7| <= tol K15 (+ a floor of
  // 1e-16 E(lambda) sr^-1 m^-1 x panel length), so the whole integral has relative error <= tol.
  SingleScatteringIntegrator(const SpectralMedium& medium, glm::dvec3 sunDirection, double relativeTolerance);

  DeterministicRadiance integrate(const ViewSegment& view, bool includeSunDisc, bool includeSingleScattering) const;

  const SunDisc& sunDisc() const { return sunDisc_; }

 private:
  // One recursive panel of the in-scattering integral; adds its K15 estimate to `radiance`.
  void integratePanel(const ViewSegment& view, double a, double b, int depth, double rayleighPhase, double miePhase,
                      ConstituentDensities* columnBefore, std::vector<double>* radiance) const;

  const SpectralMedium& medium_;
  glm::dvec3 sun_;
  double relativeTolerance_;
  ColumnIntegrator columns_;
  SunDisc sunDisc_;
};

}  // namespace firmament::reference
