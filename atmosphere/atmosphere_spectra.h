#pragma once
// Spectral inputs of the atmosphere (from core/spectrum) and the conversion of radiance at three
// wavelengths to linear Rec.709 luminance units, as in Bruneton 2017's demo: each channel c
// assumes the spectrum around it is shaped like L(lambda_c) * E_sun(lambda)/E_sun(lambda_c) *
// (lambda/lambda_c)^p, with p = -3 for sky light (Rayleigh-dominated, lambda^-4 scattering of a
// lambda^+1-ish weighting) and p = 0 for the sun's direct light, and integrates the CIE matching
// functions over 360-830 nm against it.
#include <glm/glm.hpp>
#include <vector>

namespace firmament {

// Bruneton's representative wavelengths for the three-wavelength fast path (nm).
inline constexpr glm::dvec3 kDefaultWavelengthsNm{680.0, 550.0, 440.0};
// Spectral exponents of that conversion.
inline constexpr double kSkyLambdaPower = -3.0;
inline constexpr double kSunLambdaPower = 0.0;

double solarIrradiance(double wavelengthNm);    // W m^-2 nm^-1 at the top of the atmosphere
double ozoneCrossSection(double wavelengthNm);  // m^2 per molecule

// Diagonal matrix: linear Rec.709 (cd m^-2) per unit spectral radiance (W m^-2 sr^-1 nm^-1) at each
// of the three wavelengths.
glm::dmat3 threeWavelengthRadianceToRgb(glm::dvec3 wavelengthsNm, double lambdaPower);

// Three wavelengths the GPU carries together, and how their radiance becomes linear Rec.709 cd/m².
struct SpectralBatch {
  glm::dvec3 wavelengthsNm;
  glm::dmat3 skyToRgb;  // for scattered sky light
  glm::dmat3 sunToRgb;  // for light with the sun's spectrum (sun disc, aerosol single scattering, ground)
};

// The wavelength sampling of the fast path (the `spectral_samples` knob):
//  - 3: one batch at `threeWavelengthsNm` with Bruneton's conversion (above);
//  - a multiple of 3 from 6 to 48: N uniform bins over [360, 830] nm, sampled at their centres, each
//    weighted by 683 lm/W * (XYZ->Rec.709 * CIE 1931)(lambda) * bin width: a Riemann sum of the
//    luminance integral, exact as N grows, with no assumption about the spectrum's shape (sky and sun
//    matrices are then equal).
std::vector<SpectralBatch> spectralBatches(int spectralSamples, glm::dvec3 threeWavelengthsNm);
inline constexpr double kSpectrumMinNm = 360.0;
inline constexpr double kSpectrumMaxNm = 830.0;

}  // namespace firmament
