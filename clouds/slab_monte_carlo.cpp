#include "clouds/slab_monte_carlo.h"

#include <algorithm>
#include <cmath>

#include "clouds/cloud_settings.h"
#include "common/cloud_lighting.glsl"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;

const CloudLightingSettings& defaultLighting() {
  static const CloudLightingSettings lighting;
  return lighting;
}

double dot(SlabDirection a, SlabDirection b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

double phase(double nu) {
  const CloudLightingSettings& l = defaultLighting();
  return shared::cloudPhase(l.gForward, l.gBack, l.backWeight, l.alpha, nu);
}

double uniform(std::mt19937_64& rng) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); }

// A direction at an angle from w drawn from the phase (a lobe by its weight, then HG by inversion): the
// light's direction before (or after) a scattering into (or out of) w, density p(w' . w).
SlabDirection sampleAroundByPhase(SlabDirection w, std::mt19937_64& rng) {
  const CloudLightingSettings& l = defaultLighting();
  const double g = uniform(rng) < l.backWeight ? l.gBack : l.gForward;
  const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * uniform(rng));
  const double cosTheta = std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
  const double sinTheta = std::sqrt(1.0 - cosTheta * cosTheta), phi = 2.0 * kPi * uniform(rng);
  // An orthonormal frame around w.
  const SlabDirection t = std::abs(w.z) < 0.9 ? SlabDirection{0.0, 0.0, 1.0} : SlabDirection{1.0, 0.0, 0.0};
  SlabDirection a{w.y * t.z - w.z * t.y, w.z * t.x - w.x * t.z, w.x * t.y - w.y * t.x};
  const double la = std::sqrt(dot(a, a));
  a = {a.x / la, a.y / la, a.z / la};
  const SlabDirection b{w.y * a.z - w.z * a.y, w.z * a.x - w.x * a.z, w.x * a.y - w.y * a.x};
  const double ca = sinTheta * std::cos(phi), cb = sinTheta * std::sin(phi);
  return {cosTheta * w.x + ca * a.x + cb * b.x, cosTheta * w.y + ca * a.y + cb * b.y,
          cosTheta * w.z + ca * a.z + cb * b.z};
}

template <class F>
SlabEstimate estimate(int paths, F sample) {
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < paths; ++i) {
    const double v = sample();
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / paths;
  return {mean, std::sqrt(std::max(sum2 / paths - mean * mean, 0.0) / paths)};
}

}  // namespace

SlabMonteCarlo::SlabMonteCarlo(double thickness, double mu0, uint64_t seed, double radius)
    : thickness_(thickness), mu0_(mu0), radius_(radius), sun_{std::sqrt(1.0 - mu0 * mu0), 0.0, mu0}, rng_(seed) {}

SlabEstimate SlabMonteCarlo::source(double tau, SlabDirection out, int paths) {
  return source(SlabPoint{0.0, 0.0, tau}, out, paths);
}

SlabEstimate SlabMonteCarlo::source(SlabPoint at, SlabDirection out, int paths) {
  // The light's propagation direction before it turns into `out`, drawn by the phase: weight 1.
  return estimate(paths, [&] { return walk(at, sampleAroundByPhase(out, rng_), /*countFirst=*/true); });
}

SlabEstimate SlabMonteCarlo::baseRadiance(SlabDirection out, int paths) {
  return estimate(paths, [&] { return walk(SlabPoint{0.0, 0.0, thickness_}, out, /*countFirst=*/false); });
}

bool SlabMonteCarlo::inside(SlabPoint p) const {
  return p.z >= 0.0 && p.z <= thickness_ && (std::isinf(radius_) || p.x * p.x + p.y * p.y <= radius_ * radius_);
}

// Back along the sun's direction from p: the top is z / mu0 away; the side (a finite radius) where
// |(x, y) - t (sx, 0)| = R, the larger root of sx^2 t^2 - 2 x sx t + x^2 + y^2 - R^2 = 0. The medium is
// convex, so the nearer of the two is where the ray entered.
double SlabMonteCarlo::opticalDepthToSun(SlabPoint p) const {
  const double toTop = p.z / mu0_;
  const double sx = sun_.x;
  if (std::isinf(radius_) || sx < 1e-12) return toTop;
  const double c = p.x * p.x + p.y * p.y - radius_ * radius_;
  const double disc = std::max(p.x * p.x * sx * sx - sx * sx * c, 0.0);
  const double toSide = (p.x * sx + std::sqrt(disc)) / (sx * sx);
  return std::min(toTop, std::max(toSide, 0.0));
}

// Light propagating along w arrives at p: go back against w to where it last scattered, add the sun's
// single scattering there (next-event estimation; not at the first vertex unless countFirst, so that
// only orders >= 2 arrive), and go on. Albedo 1, free paths and phase sampled exactly: weight 1. A
// straight line leaves a convex medium once, so a vertex outside ends the path.
double SlabMonteCarlo::walk(SlabPoint p, SlabDirection w, bool countFirst) {
  double light = 0.0;
  for (int vertex = 0;; ++vertex) {
    const double s = -std::log(1.0 - uniform(rng_));
    p = {p.x - s * w.x, p.y - s * w.y, p.z - s * w.z};
    if (!inside(p)) return light;
    if (countFirst || vertex > 0) light += std::exp(-opticalDepthToSun(p)) * phase(dot(sun_, w));
    w = sampleAroundByPhase(w, rng_);
  }
}

SlabPhotonResult SlabMonteCarlo::photonsThroughBase(int photons, int bins, int minOrder) {
  std::vector<long> counts(size_t(bins), 0);
  long transmitted = 0;
  for (int i = 0; i < photons; ++i) {
    double z = 0.0;
    SlabDirection w = sun_;
    for (int order = 0;; ++order) {
      z += -std::log(1.0 - uniform(rng_)) * w.z;
      if (z < 0.0) break;
      if (z > thickness_) {
        if (order >= minOrder) {
          ++transmitted;
          ++counts[size_t(std::min(bins - 1, int(w.z * bins)))];
        }
        break;
      }
      w = sampleAroundByPhase(w, rng_);
    }
  }
  SlabPhotonResult r;
  const double p = double(transmitted) / photons;
  r.flux = {p, std::sqrt(p * (1.0 - p) / photons)};
  // A bin's photons per photon carry the flux mu0 E times their share; as radiance over the bin, divide
  // by the projected solid angle pi (b^2 - a^2) of the exit cosines [a, b).
  for (int b = 0; b < bins; ++b) {
    const double lo = double(b) / bins, hi = double(b + 1) / bins;
    const double scale = mu0_ / (kPi * (hi * hi - lo * lo) * photons);
    r.radiance.push_back({counts[size_t(b)] * scale, std::sqrt(double(counts[size_t(b)])) * scale});
  }
  return r;
}

SlabDirection slabDirection(double muDown, double azimuth_deg) {
  const double s = std::sqrt(std::max(1.0 - muDown * muDown, 0.0)), phi = azimuth_deg * kPi / 180.0;
  return {s * std::cos(phi), s * std::sin(phi), muDown};
}

double slabFloorSource(double mu0, double tau, double thickness, double muDown) {
  const CloudLightingSettings& l = defaultLighting();
  const double g = shared::cloudPhaseMeanCosine(l.gForward, l.gBack, l.backWeight, l.alpha);
  return shared::cloudEscapeCorrection(mu0) * shared::cloudEddingtonSlabSource(mu0, tau, thickness, g, muDown);
}

// The source along the slant way up into the slab from the base, attenuated back to it (midpoint rule,
// 4000 steps).
double slabFloorBaseRadiance(double mu0, double thickness, double muDown, bool limb) {
  const int n = 4000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double above = thickness * (i + 0.5) / n;          // vertical optical depth above the base
    const double transmittance = std::exp(-above / muDown);  // along the way out
    const double factor = limb ? shared::cloudBaseLimbFactor(muDown, above, transmittance, 1.0) : 1.0;
    sum +=
        slabFloorSource(mu0, thickness - above, thickness, muDown) * factor * transmittance * (thickness / n) / muDown;
  }
  return sum;
}

// 2 pi integral of the radiance times mu over the exit cosines (midpoint rule, 40 angles), per mu0 E.
double slabFloorBaseFlux(double thickness, double mu0) {
  const int n = 40;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    sum += slabFloorBaseRadiance(mu0, thickness, mu, true) * mu * (1.0 / n);
  }
  return 2.0 * kPi * sum / mu0;
}

}  // namespace firmament
