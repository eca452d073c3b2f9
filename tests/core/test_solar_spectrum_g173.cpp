// The fine ASTM G-173 table and its reading through an instrument line shape (docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/solar_spectrum_g173.h"
#include "core/spectrum.h"

namespace firmament {
namespace {

// The transcription check: the mean of the fine samples in each [λ, λ + 10 nm) equals the
// atmosphere's 10-nm table (Bruneton 2017's means of the same spectrum) to its 6 digits. A mistyped
// sample moves its bin's mean by a tenth (a twentieth below 400 nm) of the typo.
TEST(SolarSpectrumG173, BinMeansAreTheAtmospheresTable) {
  const auto w = astmG173ExtraterrestrialWavelengths();
  const auto s = astmG173ExtraterrestrialIrradiance();
  ASSERT_EQ(w.size(), s.size());
  const TabulatedSpectrum& bins = solarIrradianceTopOfAtmosphere();
  int checked = 0;
  for (double start = 360.0; start + 10.0 <= kAstmG173FineLastNm + 0.5; start += 10.0) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < w.size(); ++i)
      if (w[i] >= start - 1e-9 && w[i] < start + 10.0 - 1e-9) sum += s[i], ++n;
    ASSERT_EQ(n, start < 400.0 ? 20 : 10) << start;
    const double binValue = bins.values[size_t(std::lround((start - bins.firstWavelength) / bins.spacing))];
    EXPECT_NEAR(sum / n, binValue, 1e-5 * binValue) << "bin starting at " << start << " nm";
    ++checked;
  }
  EXPECT_EQ(checked, 38);  // 360-740 nm
}

// A line shape much narrower than the sampling reads the piecewise-linear table itself.
TEST(SolarSpectrumG173, ANarrowLineShapeReadsTheTable) {
  EXPECT_NEAR(astmG173ExtraterrestrialSeenWithResolution(500.0, 0.02), 1.916, 1e-3);
  EXPECT_NEAR(astmG173ExtraterrestrialSeenWithResolution(395.25, 0.02), 0.5 * (1.245 + 1.3245), 1e-4);
}

// Smoothing keeps the energy: over 400-700 nm the 3-nm reading's mean equals the table's (within
// 0.2 %; only the ends, where the kernel reaches past the range, differ).
TEST(SolarSpectrumG173, TheLineShapeKeepsTheEnergy) {
  double reading = 0.0, table = 0.0;
  int n = 0;
  for (double l = 400.0; l <= 700.0 + 1e-9; l += 0.25, ++n) {
    reading += astmG173ExtraterrestrialSeenWithResolution(l, 3.0);
    table += interpolateSpectrum(astmG173ExtraterrestrialWavelengths(), astmG173ExtraterrestrialIrradiance(), l);
  }
  EXPECT_NEAR(reading / n, table / n, 2e-3 * table / n);
}

// What the reading is for: between Ca II H and K (393.4 / 396.8 nm) a 3-nm instrument sees much less
// than the 10-nm bin the atmosphere uses; in the continuum near 550 nm the two agree within 2 %.
TEST(SolarSpectrumG173, TheCalciumLinesDarkenThe3NmReading) {
  EXPECT_LT(astmG173ExtraterrestrialSeenWithResolution(395.25, 3.0), 0.8 * solarIrradianceTopOfAtmosphere()(395.25));
  EXPECT_NEAR(astmG173ExtraterrestrialSeenWithResolution(548.0, 3.0), solarIrradianceTopOfAtmosphere()(548.0),
              0.02 * solarIrradianceTopOfAtmosphere()(548.0));
}

TEST(SolarSpectrumG173, ALineShapeOutsideTheTableThrows) {
  EXPECT_THROW(astmG173ExtraterrestrialSeenWithResolution(341.0, 3.0), std::out_of_range);
  EXPECT_THROW(astmG173ExtraterrestrialSeenWithResolution(739.0, 3.0), std::out_of_range);
  EXPECT_THROW(astmG173ExtraterrestrialSeenWithResolution(500.0, 0.0), std::out_of_range);
  EXPECT_NO_THROW(astmG173ExtraterrestrialSeenWithResolution(360.0, 8.0));
}

}  // namespace
}  // namespace firmament
