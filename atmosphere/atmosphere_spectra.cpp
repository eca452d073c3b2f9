#include "atmosphere/atmosphere_spectra.h"

#include <cmath>
#include <stdexcept>

#include "core/spectrum.h"

namespace firmament {

double solarIrradiance(double wavelengthNm) { return solarIrradianceTopOfAtmosphere()(wavelengthNm); }

double ozoneCrossSection(double wavelengthNm) { return ozoneAbsorptionCrossSection()(wavelengthNm); }

glm::dmat3 threeWavelengthRadianceToRgb(glm::dvec3 wavelengthsNm, double lambdaPower) {
  glm::dvec3 k(0.0);
  const glm::dmat3& toRgb = xyzToLinearRec709Matrix();
  for (int c = 0; c < 3; ++c) {
    double lambdaC = wavelengthsNm[c];
    double solarC = solarIrradiance(lambdaC);
    double sum = 0.0;
    for (int lambda = 360; lambda <= 830; ++lambda) {  // 1 nm steps
      glm::dvec3 rgbBar = toRgb * cie1931ColorMatching(double(lambda));
      sum += rgbBar[c] * solarIrradiance(lambda) / solarC * std::pow(double(lambda) / lambdaC, lambdaPower);
    }
    k[c] = kMaxLuminousEfficacy * sum;
  }
  return glm::dmat3(k.x, 0.0, 0.0, 0.0, k.y, 0.0, 0.0, 0.0, k.z);
}

std::vector<SpectralBatch> spectralBatches(int spectralSamples, glm::dvec3 threeWavelengthsNm) {
  if (spectralSamples == 3)
    return {{threeWavelengthsNm, threeWavelengthRadianceToRgb(threeWavelengthsNm, kSkyLambdaPower),
             threeWavelengthRadianceToRgb(threeWavelengthsNm, kSunLambdaPower)}};
  if (spectralSamples < 6 || spectralSamples % 3 != 0 || spectralSamples > 48)
    throw std::invalid_argument("spectral samples must be 3 or a multiple of 3 in [6, 48]");
  const double width = (kSpectrumMaxNm - kSpectrumMinNm) / double(spectralSamples);
  const glm::dmat3& toRgb = xyzToLinearRec709Matrix();
  std::vector<SpectralBatch> batches;
  for (int b = 0; b < spectralSamples / 3; ++b) {
    SpectralBatch batch;
    for (int i = 0; i < 3; ++i) {
      double lambda = kSpectrumMinNm + (double(3 * b + i) + 0.5) * width;
      batch.wavelengthsNm[i] = lambda;
      batch.skyToRgb[i] = kMaxLuminousEfficacy * width * (toRgb * cie1931ColorMatching(lambda));
    }
    batch.sunToRgb = batch.skyToRgb;
    batches.push_back(batch);
  }
  return batches;
}

}  // namespace firmament
