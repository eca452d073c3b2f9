#pragma once
// The ASTM G-173-03 extraterrestrial solar spectrum at its own sampling, and how a spectroradiometer
// with a given line shape reads it. The atmosphere itself uses 10-nm means of the same spectrum
// (core/spectrum.h); this finer table is for comparisons with measured spectra, where the Fraunhofer
// lines (Ca II H and K at 393/397 nm, the G band at 430 nm) are narrower than a 10-nm bin but wider
// than the instrument's resolution (docs/validation.md).
#include <span>

namespace firmament {

// W m^-2 nm^-1 at 1 au, 340-400 nm every 0.5 nm and 401-740 nm every 1 nm, as ASTM G173-03
// ("Standard Tables for Reference Solar Spectral Irradiances", ASTM International 2003; derived
// from SMARTS 2.9.2, Gueymard 2004) tabulates its extraterrestrial column.
std::span<const double> astmG173ExtraterrestrialWavelengths();
std::span<const double> astmG173ExtraterrestrialIrradiance();
inline constexpr double kAstmG173FineFirstNm = 340.0, kAstmG173FineLastNm = 740.0;

// The spectrum as an instrument with a Gaussian line shape of full width at half maximum `fwhmNm`
// reads it at `wavelengthNm`: ∫ S(λ') g(λ' − λ) dλ' / ∫ g, S linear between the samples, the kernel
// cut at ±4σ (σ = FWHM / (2 √(2 ln 2))). Throws std::out_of_range where the kernel leaves the table.
double astmG173ExtraterrestrialSeenWithResolution(double wavelengthNm, double fwhmNm);

}  // namespace firmament
