// Spectral tables and spectral -> colour conversion (core/spectrum.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include "core/spectrum.h"

namespace firmament {
namespace {

glm::dvec2 chromaticity(const glm::dvec3& xyz) {
  double sum = xyz.x + xyz.y + xyz.z;
  return {xyz.x / sum, xyz.y / sum};
}

TEST(Spectrum, TablesCoverTheVisible) {
  for (const TabulatedSpectrum* s : {&cie1931X(), &cie1931Y(), &cie1931Z()}) {
    EXPECT_EQ(s->values.size(), 95u);
    EXPECT_DOUBLE_EQ(s->firstWavelength, 360.0);
    EXPECT_DOUBLE_EQ(s->lastWavelength(), 830.0);
  }
  for (const TabulatedSpectrum* s : {&solarIrradianceTopOfAtmosphere(), &ozoneAbsorptionCrossSection()}) {
    EXPECT_EQ(s->values.size(), 48u);
    EXPECT_DOUBLE_EQ(s->firstWavelength, 360.0);
    EXPECT_DOUBLE_EQ(s->lastWavelength(), 830.0);
    EXPECT_TRUE(std::all_of(s->values.begin(), s->values.end(), [](double v) { return v > 0.0; }));
  }
}

TEST(Spectrum, TabulatedInterpolation) {
  const TabulatedSpectrum& y = cie1931Y();
  EXPECT_DOUBLE_EQ(y(555.0), 1.0);
  EXPECT_DOUBLE_EQ(y(830.0), 4.5181e-07);
  EXPECT_NEAR(y(557.5), (1.0 + 0.995) / 2, 1e-15);
  EXPECT_EQ(y(359.9), 0.0);
  EXPECT_EQ(y(830.1), 0.0);
  std::array<double, 3> wavelengths = {400.0, 410.0, 450.0}, values = {1.0, 3.0, 7.0};
  EXPECT_DOUBLE_EQ(interpolateSpectrum(wavelengths, values, 400.0), 1.0);
  EXPECT_DOUBLE_EQ(interpolateSpectrum(wavelengths, values, 405.0), 2.0);
  EXPECT_DOUBLE_EQ(interpolateSpectrum(wavelengths, values, 440.0), 6.0);
  EXPECT_DOUBLE_EQ(interpolateSpectrum(wavelengths, values, 450.0), 7.0);
  EXPECT_EQ(interpolateSpectrum(wavelengths, values, 399.0), 0.0);
  EXPECT_EQ(interpolateSpectrum(wavelengths, values, 451.0), 0.0);
}

TEST(Spectrum, CieYIntegral) {
  // CIE 15:2004: Σȳ(λ)Δλ = 106.857 (1 nm table); the 5 nm table gives the same to 0.001.
  EXPECT_NEAR(cie1931Y().integral(), 106.857, 0.001);
  // Integrating a flat 1 W m^-2 nm^-1 spectrum at 1 nm against the interpolated CMFs gives 683 · 106.857.
  TabulatedSpectrum flat{300.0, 600.0, {1.0, 1.0}};
  std::printf("sum of y-bar: 5 nm table %.4f, 1 nm interpolated %.4f\n", cie1931Y().integral(),
              spectrumToXyz(flat).y / kMaxLuminousEfficacy);
  EXPECT_NEAR(spectrumToXyz(flat).y / kMaxLuminousEfficacy, 106.857, 0.01);
}

TEST(Spectrum, EqualEnergyIsTheWhitePoint) {
  std::array<double, 2> wavelengths = {350.0, 850.0}, ones = {1.0, 1.0};
  glm::dvec2 xy = chromaticity(spectrumToXyz(wavelengths, ones));
  std::printf("equal-energy white: x %.5f y %.5f\n", xy.x, xy.y);
  EXPECT_NEAR(xy.x, 1.0 / 3.0, 2e-4);
  EXPECT_NEAR(xy.y, 1.0 / 3.0, 2e-4);
}

TEST(Spectrum, LuminousEfficacyAt555nm) {
  EXPECT_DOUBLE_EQ(kMaxLuminousEfficacy * cie1931ColorMatching(555.0).y, 683.0);
  // A 1 W/m^2 line at 555 nm (a triangle 2 nm wide and 1 W m^-2 nm^-1 high) gives 683 lux.
  std::array<double, 3> wavelengths = {554.0, 555.0, 556.0}, values = {0.0, 1.0, 0.0};
  EXPECT_NEAR(spectrumToXyz(wavelengths, values).y, 683.0, 1e-9);
  // Elsewhere the efficacy is lower: 1 W at 450 nm gives 683 · 0.038 lm.
  std::array<double, 3> blueWavelengths = {449.0, 450.0, 451.0};
  EXPECT_NEAR(spectrumToXyz(blueWavelengths, values).y, 683.0 * 0.038, 1e-9);
}

TEST(Spectrum, SolarIrradianceIntegral) {
  // The 48 bins cover 360-840 nm: 745.44 W/m^2 of the ~1361-1366 W/m^2 solar constant (a 5772 K
  // black body scaled to 1361 W/m^2 puts 728 W/m^2 there).
  double total = solarIrradianceTopOfAtmosphere().integral();
  glm::dvec3 xyz = spectrumToXyz(solarIrradianceTopOfAtmosphere());
  std::printf("solar irradiance 360-840 nm: %.2f W/m^2, illuminance %.0f lx, xy (%.4f, %.4f)\n", total, xyz.y,
              chromaticity(xyz).x, chromaticity(xyz).y);
  EXPECT_NEAR(total, 745.44, 0.01);
  // Extraterrestrial solar illuminance is about 128-135 klx (e.g. 133.8 klx from Wehrli 1985 with
  // 683 lm/W); and the Sun above the atmosphere is near x, y = 0.32-0.33.
  EXPECT_GT(xyz.y, 125e3);
  EXPECT_LT(xyz.y, 140e3);
  EXPECT_NEAR(chromaticity(xyz).x, 0.325, 0.01);
  EXPECT_NEAR(chromaticity(xyz).y, 0.335, 0.01);
}

TEST(Spectrum, OzonePeaksInTheChappuisBand) {
  const TabulatedSpectrum& ozone = ozoneAbsorptionCrossSection();
  auto peak = std::max_element(ozone.values.begin(), ozone.values.end());
  EXPECT_DOUBLE_EQ(ozone.firstWavelength + ozone.spacing * double(peak - ozone.values.begin()), 600.0);
  EXPECT_NEAR(*peak, 5.0e-25, 0.1e-25);  // m^2; ~5e-21 cm^2 at the Chappuis maximum
}

TEST(Spectrum, XyzToRec709) {
  // IEC 61966-2-1 (sRGB) matrix, four decimals; ours is derived from the primaries in full precision.
  const double iec[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  const glm::dmat3& m = xyzToLinearRec709Matrix();
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column) EXPECT_NEAR(m[column][row], iec[row][column], 5e-4);
  // D65 white maps to R = G = B = Y.
  glm::dvec3 d65(0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290);
  glm::dvec3 rgb = xyzToLinearRec709(d65);
  EXPECT_NEAR(rgb.r, 1.0, 1e-12);
  EXPECT_NEAR(rgb.g, 1.0, 1e-12);
  EXPECT_NEAR(rgb.b, 1.0, 1e-12);
}

TEST(Spectrum, Rec709KeepsLuminance) {
  glm::dvec3 xyz = spectrumToXyz(solarIrradianceTopOfAtmosphere());
  glm::dvec3 rgb = spectrumToLinearRec709(solarIrradianceTopOfAtmosphere());
  // BT.709 luminance coefficients (the Y row of the RGB -> XYZ matrix).
  EXPECT_NEAR(0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b, xyz.y, 1e-4 * xyz.y);
  EXPECT_GT(rgb.r, 0.0);
  EXPECT_GT(rgb.g, 0.0);
  EXPECT_GT(rgb.b, 0.0);
}

}  // namespace
}  // namespace firmament
