#include "atmosphere/atmosphere_spectra.h"

#include <cmath>

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

}  // namespace firmament
