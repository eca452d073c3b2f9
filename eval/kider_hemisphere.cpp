#include "eval/kider_hemisphere.h"

#include <cmath>

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Catmull-Rom through a0 (t = 0) and a1 (t = 1), with tangents (a1 - am1) / 2 and (a2 - a0) / 2.
double catmullRom(double t, double am1, double a0, double a1, double a2) {
  return 0.5 * (2.0 * a0 + t * ((a1 - am1) +
                                t * ((2.0 * am1 - 5.0 * a0 + 4.0 * a1 - a2) + t * (-am1 + 3.0 * a0 - 3.0 * a1 + a2))));
}

double wrapAzimuth(double azimuth) {
  azimuth = std::fmod(azimuth, 2.0 * kPi);
  return azimuth < 0 ? azimuth + 2.0 * kPi : azimuth;
}

}  // namespace

std::optional<KiderHemisphere> KiderHemisphere::fromSamples(const std::vector<RingSample>& samples) {
  KiderHemisphere sky;
  std::vector<std::vector<bool>> filled(5);
  for (int k = 0; k < 5; ++k) {
    sky.rings_[k].assign(k == 0 ? 1 : 8 * k, 0.0);
    filled[k].assign(sky.rings_[k].size(), false);
  }
  for (const RingSample& s : samples) {
    // Ring radius in the unit disk: cos(zenith) = sin(elevation) = 1 - r^2, and r = 2k / 9.
    const double u = 4.5 * std::sqrt(std::max(0.0, 1.0 - std::sin(s.elevation)));
    const long k = std::lround(u);
    if (k < 0 || k > 4 || std::abs(u - double(k)) > 1e-3) return std::nullopt;
    long n = 0;
    if (k > 0) {
      const double cell = wrapAzimuth(s.azimuth) / (kPi / (4.0 * double(k)));
      n = std::lround(cell);
      if (std::abs(cell - double(n)) > 1e-3) return std::nullopt;
      n %= 8 * k;
    }
    if (filled[k][n]) return std::nullopt;
    filled[k][n] = true;
    sky.rings_[k][n] = s.value;
  }
  for (const auto& ring : filled)
    for (bool f : ring)
      if (!f) return std::nullopt;
  return sky;
}

// The zenith gradient from the 8 samples of ring 1 at azimuths phi_n = n pi / 4: the published
// estimate is D(a) = sum_n v_n cos(a - phi_n) / (2 + 2 sqrt 2) (a plane fitted with the diagonal
// neighbours weighted 1/sqrt 2), in value per ring step.
double KiderHemisphere::zenithSlope(double azimuth) const {
  double sum = 0.0;
  for (int n = 0; n < 8; ++n) sum += rings_[1][n] * std::cos(azimuth - n * kPi / 4.0);
  return sum / (2.0 + 2.0 * std::sqrt(2.0));
}

double KiderHemisphere::ring(int k, double azimuth) const {
  // Ring -1: chosen so that the central difference (R(1) - R(-1)) / 2 at the zenith is its slope.
  if (k < 0) return ring(1, azimuth) - 2.0 * zenithSlope(azimuth);
  // Beyond the lowest ring, towards the horizon: the second difference is held constant.
  if (k > 4) return ring(k - 3, azimuth) - 3.0 * ring(k - 2, azimuth) + 3.0 * ring(k - 1, azimuth);
  if (k == 0) return rings_[0][0];
  const auto& values = rings_[k];
  const int count = int(values.size());
  const double u = wrapAzimuth(azimuth) / (kPi / (4.0 * k));
  const int n = int(std::floor(u));
  auto at = [&](int i) { return values[size_t(((i % count) + count) % count)]; };
  return catmullRom(u - n, at(n - 1), at(n), at(n + 1), at(n + 2));
}

double KiderHemisphere::operator()(double zenith, double azimuth) const {
  const double u = 4.5 * std::sqrt(std::max(0.0, 1.0 - std::cos(zenith)));
  const int k = int(std::floor(u));
  return catmullRom(u - k, ring(k - 1, azimuth), ring(k, azimuth), ring(k + 1, azimuth), ring(k + 2, azimuth));
}

double publishedMirrorAsymmetry(const KiderHemisphere& sky, double axisAzimuth) {
  double sum = 0.0;
  for (int i = 0; i < 16; ++i) {
    const double zenith = std::acos((i + 0.5) / 16.0);
    for (int j = 0; j < 64; ++j) {
      const double azimuth = 2.0 * kPi * j / 64.0;
      sum += std::abs(sky(zenith, azimuth) - sky(zenith, 2.0 * axisAzimuth - azimuth));
    }
  }
  return sum;
}

double refitSunAzimuthByPublishedSymmetry(const KiderHemisphere& sky, double computedAzimuth, double halfRange,
                                          double step) {
  return minimiseOnAzimuthGrid(computedAzimuth, halfRange, step,
                               [&](double azimuth) { return publishedMirrorAsymmetry(sky, azimuth); });
}

}  // namespace firmament
