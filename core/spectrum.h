#pragma once
// Spectral data and spectral -> colour conversion: the CIE 1931 2° observer, the solar irradiance at
// the top of the atmosphere, the ozone absorption cross-section, and XYZ -> linear Rec.709.
// Wavelengths in nanometres; spectral quantities per nanometre (docs/spectra.md).
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace firmament {

// Maximum luminous efficacy of radiation for photopic vision, lm/W: by the SI definition of the candela,
// 683 lm/W at 540 THz (555.016 nm in standard air), where ȳ = 1.
inline constexpr double kMaxLuminousEfficacy = 683.0;

// A spectrum sampled at evenly spaced wavelengths: values[i] at firstWavelength + i * spacing (nm).
struct TabulatedSpectrum {
  double firstWavelength = 0.0;
  double spacing = 1.0;
  std::vector<double> values;

  double lastWavelength() const { return firstWavelength + spacing * double(values.size() - 1); }
  // Linear interpolation; zero outside [firstWavelength, lastWavelength] (no data is no energy).
  double operator()(double wavelength) const;
  // Σ values · spacing: the integral of the piecewise-constant spectrum whose bins start (or, for
  // functions vanishing at both ends like the CMFs, are centred) at the samples, as CIE 15 sums tables.
  double integral() const;
};

// Linear interpolation of samples at increasing, not necessarily even, wavelengths; zero outside.
double interpolateSpectrum(std::span<const double> wavelengths, std::span<const double> values, double wavelength);

// CIE 1931 2° standard observer colour-matching functions x̄, ȳ, z̄, 360-830 nm every 5 nm
// (CIE 15:2004 table T.4; digits as distributed by CVRL, cvrl.org "ciexyz31.txt").
const TabulatedSpectrum& cie1931X();
const TabulatedSpectrum& cie1931Y();
const TabulatedSpectrum& cie1931Z();
// (x̄, ȳ, z̄) at a wavelength, linearly interpolated.
glm::dvec3 cie1931ColorMatching(double wavelength);

// Solar spectral irradiance at the top of the atmosphere at 1 au, W m^-2 nm^-1, 360-830 nm every 10 nm.
// Each value is the mean of the ASTM G-173-03 extraterrestrial spectrum over [λ, λ + 10 nm), as
// tabulated by Bruneton (2017), precomputed_atmospheric_scattering, atmosphere/demo/demo.cc.
// Its integral (bins 360-840 nm) is 745.44 W/m^2 of the ~1366 W/m^2 total.
const TabulatedSpectrum& solarIrradianceTopOfAtmosphere();

// Ozone (O3) absorption cross-section, m^2 per molecule, 360-830 nm every 10 nm: Serdyuchenko et al.
// (2014), "High spectral resolution ozone absorption cross-sections", Atmos. Meas. Tech. 7, 625 (IUP
// Bremen o3spectra2011, 233 K), averaged over [λ, λ + 10 nm) as tabulated by Bruneton (2017).
const TabulatedSpectrum& ozoneAbsorptionCrossSection();

// XYZ -> linear Rec.709 (sRGB primaries, D65 white), rgb = M * xyz. Derived in double precision from the
// ITU-R BT.709 primaries R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06) and white D65 (0.3127, 0.3290);
// equals the IEC 61966-2-1 matrix (3.2406, -1.5372, -0.4986; ...) to its four decimals.
const glm::dmat3& xyzToLinearRec709Matrix();
glm::dvec3 xyzToLinearRec709(const glm::dvec3& xyz);

// Tristimulus values of a spectral quantity: XYZ = 683 lm/W · ∫ S(λ) (x̄, ȳ, z̄)(λ) dλ over 360-830 nm,
// with S linearly interpolated and summed at 1 nm. For spectral radiance in W m^-2 sr^-1 nm^-1, Y is the
// luminance in cd/m^2; for spectral irradiance in W m^-2 nm^-1, Y is the illuminance in lux.
glm::dvec3 spectrumToXyz(const TabulatedSpectrum& spectrum);
glm::dvec3 spectrumToXyz(std::span<const double> wavelengths, std::span<const double> values);
// The same in linear Rec.709, photometric scale kept: 0.2126 R + 0.7152 G + 0.0722 B equals Y.
glm::dvec3 spectrumToLinearRec709(const TabulatedSpectrum& spectrum);
glm::dvec3 spectrumToLinearRec709(std::span<const double> wavelengths, std::span<const double> values);

}  // namespace firmament
