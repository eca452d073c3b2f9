#include "atmosphere/reference_path_tracer.h"

#include <algorithm>
#include <cmath>

#include "common/atmosphere_lut.glsl"

namespace firmament::reference {
namespace {

// Divides f and every p_j by pbar = mean_j p_j: the ratio f / pbar, which is all the estimator
// uses, is unchanged, and the numbers stay near 1 however long the path. Returns false when no
// technique could have produced the path (pbar = 0).
bool renormalise(std::vector<double>& f, std::vector<double>& p) {
  double mean = 0.0;
  for (double v : p) mean += v;
  mean /= double(p.size());
  if (!(mean > 0.0) || !std::isfinite(mean)) return false;
  const double inverse = 1.0 / mean;
  for (double& v : f) v *= inverse;
  for (double& v : p) v *= inverse;
  return true;
}

// Probability of choosing the Rayleigh lobe at a scattering event had wavelength i been the hero:
// sigma_R / (sigma_R + sigma_M); 1/2 where nothing scatters (any valid choice keeps the mixture a
// density).
double rayleighLobeProbability(const SpectralMedium& m, int i, ConstituentDensities d) {
  const double rayleigh = m.rayleighScattering(i) * d.x;
  const double mie = m.mieScattering(i) * d.y;
  return rayleigh + mie > 0.0 ? rayleigh / (rayleigh + mie) : 0.5;
}

glm::dvec3 directionAround(glm::dvec3 axis, double cosine, double azimuth) {
  glm::dvec3 t, b;
  orthonormalBasis(axis, &t, &b);
  const double sine = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
  return glm::normalize(cosine * axis + sine * (std::cos(azimuth) * t + std::sin(azimuth) * b));
}

}  // namespace

double sampleRayleighCosine(double u) {
  // CDF F(nu) = 3/8 (nu + nu^3/3 + 4/3) = u  <=>  nu^3 + 3 nu + 4 - 8 u = 0, a depressed cubic with
  // one real root (Cardano): with z = 4 u - 2, A = cbrt(z + sqrt(z^2 + 1)), nu = A - 1/A (since
  // cbrt(z - sqrt(z^2 + 1)) = -1/A).
  const double z = 4.0 * u - 2.0;
  const double a = std::cbrt(z + std::sqrt(z * z + 1.0));
  return std::clamp(a - 1.0 / a, -1.0, 1.0);
}

double sampleHenyeyGreensteinCosine(double g, double u) {
  // Inverse CDF of the HG distribution of nu (pbrt-v4, SampleHenyeyGreenstein):
  //   s = (1 - g^2) / (1 - g + 2 g u),  nu = (1 + g^2 - s^2) / (2 g);  nu = 2u - 1 for g -> 0.
  if (std::abs(g) < 1e-4) return 2.0 * u - 1.0;
  const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

PathTracer::PathTracer(const SpectralMedium& medium, glm::dvec3 sunDirection, const PathTracerSettings& settings)
    : medium_(medium),
      sun_(glm::normalize(sunDirection)),
      settings_(settings),
      columns_(medium, settings.opticalDepthTolerance) {}

PathTracer::PathStatistics& PathTracer::threadStatistics() {
  thread_local PathStatistics statistics;
  return statistics;
}

PreparedViewRay PathTracer::prepare(const ViewSegment& view) const {
  PreparedViewRay ray;
  ray.view = view;
  if (!view.inAtmosphere) return ray;
  columns_.forEachPanel(view.segment, [&](const ColumnPanel& panel) {
    ray.panels.push_back(panel);
    ray.column = panel.columnBefore + panel.column;
    return true;
  });
  return ray;
}

void PathTracer::sample(const PreparedViewRay& ray, Random& random, std::vector<double>& contribution) const {
  const int n = medium_.wavelengthCount();
  contribution.assign(size_t(n), 0.0);
  if (!ray.view.inAtmosphere) return;
  threadStatistics().paths++;
  std::vector<double> f(static_cast<size_t>(n)), p(static_cast<size_t>(n));
  const int hero = std::min(int(random.uniform() * n), n - 1);

  // (1) A path through a collision on the view segment, conditioned on colliding:
  //     t solves tau_h(0, t) = -ln(1 - u (1 - T_h(0, D))).
  const double heroTotal = glm::dot(medium_.extinctionPerDensity(hero), ray.column);
  const double u = random.uniform();
  if (heroTotal > 0.0) {
    const double target = -std::log1p(u * std::expm1(-heroTotal));
    const glm::dvec3 weights = medium_.extinctionPerDensity(hero);
    // The panel where the cumulative optical depth passes the target, then the shared inversion on
    // a one-panel segment view of it.
    auto panel = std::find_if(ray.panels.begin(), ray.panels.end(), [&](const ColumnPanel& pn) {
      return glm::dot(weights, pn.columnBefore + pn.column) >= target;
    });
    if (panel == ray.panels.end()) panel = ray.panels.end() - 1;
    // Re-base the segment at the panel start so sampleFreePath integrates only this panel.
    RaySegment sub;
    sub.r = ray.view.segment.radiusAt(panel->start);
    sub.mu = (ray.view.segment.r * ray.view.segment.mu + panel->start) / sub.r;
    sub.length = panel->end - panel->start;
    const FreePathSample s =
        sampleFreePath(columns_, sub, weights, std::max(target - glm::dot(weights, panel->columnBefore), 0.0));
    const double t = panel->start + (s.collided ? s.distance : sub.length);
    const ConstituentDensities column = panel->columnBefore + s.columnBefore;
    const ConstituentDensities d = s.collided ? s.densitiesAtEnd : medium_.densitiesAt(ray.view.segment.radiusAt(t));
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 beta = medium_.extinctionPerDensity(j);
      const double transmittance = std::exp(-glm::dot(beta, column));
      const double collisionProbability = -std::expm1(-glm::dot(beta, ray.column));
      f[size_t(j)] = transmittance;
      p[size_t(j)] = collisionProbability > 0.0 ? glm::dot(beta, d) * transmittance / collisionProbability : 0.0;
    }
    const glm::dvec3 x = ray.view.origin + ray.view.direction * t;
    if (renormalise(f, p)) continuePath(x, ray.view.direction, VertexKind::Medium, d, hero, f, p, random, contribution);
  }

  // (2) When the view ray ends on the ground: a path from the ground point, weight T(0, D).
  if (ray.view.hitsGround) {
    for (int j = 0; j < n; ++j) {
      f[size_t(j)] = std::exp(-glm::dot(medium_.extinctionPerDensity(j), ray.column));
      p[size_t(j)] = 1.0;
    }
    const glm::dvec3 ground =
        glm::normalize(ray.view.origin + ray.view.direction * ray.view.segment.length) * medium_.groundRadius();
    continuePath(ground, ray.view.direction, VertexKind::Ground, ConstituentDensities(0.0), hero, f, p, random,
                 contribution);
  }
}

FreePathSample PathTracer::sampleSegment(const RaySegment& segment, int hero, bool forced, double u,
                                         ConstituentDensities* segmentColumn) const {
  const glm::dvec3 weights = medium_.extinctionPerDensity(hero);
  if (!forced) {
    // tau_h(0, t) = -ln(1 - u): exponential free path; no collision when the segment is thinner.
    return sampleFreePath(columns_, segment, weights, -std::log1p(-u));
  }
  // Conditioned on a collision: tau_h(0, t) = -ln(1 - u (1 - T_h(0, L))), which needs the whole
  // segment's column first (also for every p_j's normalisation).
  *segmentColumn = columns_.column(segment);
  const double total = glm::dot(weights, *segmentColumn);
  if (!(total > 0.0)) return FreePathSample{false, segment.length, *segmentColumn, ConstituentDensities(0.0)};
  FreePathSample s = sampleFreePath(columns_, segment, weights, -std::log1p(u * std::expm1(-total)));
  if (!s.collided) {
    // Rounding put the target a hair past the end: collide at the end.
    s.collided = true;
    s.distance = segment.length;
    s.densitiesAtEnd = medium_.densitiesAt(segment.radiusAt(segment.length));
  }
  return s;
}

void PathTracer::nextEvent(glm::dvec3 x, glm::dvec3 incoming, VertexKind kind, ConstituentDensities d,
                           const std::vector<double>& f, std::vector<double>& contribution) const {
  const int n = medium_.wavelengthCount();
  const double r = glm::length(x);
  const double muSun = glm::dot(x, sun_) / r;
  if (kind == VertexKind::Ground && muSun <= 0.0) return;
  ConstituentDensities sunColumn;
  if (!columns_.columnToSun(r, muSun, &sunColumn)) return;  // the planet hides the sun
  if (kind == VertexKind::Medium) {
    const double nu = std::clamp(glm::dot(incoming, sun_), -1.0, 1.0);
    const double phaseR = shared::rayleighPhase(nu);
    const double phaseM = shared::cornetteShanksPhase(medium_.miePhaseG(), nu);
    for (int i = 0; i < n; ++i) {
      const double scattering = medium_.rayleighScattering(i) * d.x * phaseR + medium_.mieScattering(i) * d.y * phaseM;
      contribution[size_t(i)] += f[size_t(i)] * scattering * medium_.solarIrradiance(i) *
                                 std::exp(-glm::dot(medium_.extinctionPerDensity(i), sunColumn));
    }
  } else {
    for (int i = 0; i < n; ++i)
      contribution[size_t(i)] += f[size_t(i)] * medium_.groundAlbedo(i) / shared::kPi * muSun *
                                 medium_.solarIrradiance(i) *
                                 std::exp(-glm::dot(medium_.extinctionPerDensity(i), sunColumn));
  }
}

void PathTracer::continuePath(glm::dvec3 x, glm::dvec3 incoming, VertexKind kind, ConstituentDensities d, int hero,
                              std::vector<double>& f, std::vector<double>& p, Random& random,
                              std::vector<double>& contribution) const {
  const int n = medium_.wavelengthCount();
  PathStatistics& stats = threadStatistics();
  double rouletteReference = 0.0;
  for (double v : f) rouletteReference = std::max(rouletteReference, v);
  for (int event = 1;; ++event) {
    stats.events++;
    stats.longestPath = std::max(stats.longestPath, event);
    // Vertex `event` of the path: the light reaching the camera through it from the sun has
    // order `event`; order 1 belongs to the deterministic integrator.
    if (event >= 2) nextEvent(x, incoming, kind, d, f, contribution);
    if (event >= settings_.maxBounces) {
      stats.capped++;
      return;
    }
    if (event >= settings_.rouletteStartBounce) {
      // Survive with q = min(1, max_lambda f / f_reference) and divide by q (unbiased).
      double largest = 0.0;
      for (double v : f) largest = std::max(largest, v);
      const double q = rouletteReference > 0.0 ? std::min(1.0, largest / rouletteReference) : 0.0;
      if (!(random.uniform() < q)) {
        stats.rouletteKills++;
        return;
      }
      for (double& v : f) v /= q;
    }

    // New direction.
    glm::dvec3 outgoing;
    if (kind == VertexKind::Medium) {
      const double lobe = random.uniform();
      const double u1 = random.uniform(), u2 = random.uniform();
      const double nu = lobe < rayleighLobeProbability(medium_, hero, d)
                            ? sampleRayleighCosine(u1)
                            : sampleHenyeyGreensteinCosine(medium_.miePhaseG(), u1);
      outgoing = directionAround(incoming, nu, 2.0 * shared::kPi * u2);
      const double cosine = std::clamp(glm::dot(incoming, outgoing), -1.0, 1.0);
      const double phaseR = shared::rayleighPhase(cosine);
      const double phaseCS = shared::cornetteShanksPhase(medium_.miePhaseG(), cosine);
      const double phaseHG = shared::henyeyGreensteinPhase(medium_.miePhaseG(), cosine);
      for (int j = 0; j < n; ++j) {
        f[size_t(j)] *= medium_.rayleighScattering(j) * d.x * phaseR + medium_.mieScattering(j) * d.y * phaseCS;
        const double pr = rayleighLobeProbability(medium_, j, d);
        p[size_t(j)] *= pr * phaseR + (1.0 - pr) * phaseHG;
      }
    } else {
      // Cosine-weighted about the ground normal (Malley's method): the cos/pi of the BRDF and of
      // the pdf cancel, leaving the albedo.
      const glm::dvec3 normal = glm::normalize(x);
      const double u1 = random.uniform(), u2 = random.uniform();
      outgoing = directionAround(normal, std::sqrt(std::max(u1, 1e-300)), 2.0 * shared::kPi * u2);
      for (int j = 0; j < n; ++j) f[size_t(j)] *= medium_.groundAlbedo(j);
    }
    if (!renormalise(f, p)) return;

    // Free flight along the new direction to a collision, the ground, or out of the atmosphere.
    const double r = glm::length(x);
    bool hitsGround = false;
    const RaySegment segment = segmentToBoundary(medium_, r, glm::dot(x, outgoing) / r, &hitsGround);
    // Segment event + 1 leaves vertex `event` (segment 1 is the view ray).
    const bool forced = !hitsGround && event + 1 <= settings_.forcedSegments;
    ConstituentDensities segmentColumn(0.0);
    const FreePathSample s = sampleSegment(segment, hero, forced, random.uniform(), &segmentColumn);
    if (!s.collided && !hitsGround) return;  // escaped to space: the sun is reached by next events only
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 beta = medium_.extinctionPerDensity(j);
      const double transmittance = std::exp(-glm::dot(beta, s.columnBefore));
      f[size_t(j)] *= transmittance;
      double pdf = s.collided ? transmittance * glm::dot(beta, s.densitiesAtEnd) : transmittance;
      if (forced) {
        // Conditioned on colliding: divide by the collision probability 1 - T_j(segment).
        const double collisionProbability = -std::expm1(-glm::dot(beta, segmentColumn));
        pdf = collisionProbability > 0.0 ? pdf / collisionProbability : 0.0;
      }
      p[size_t(j)] *= pdf;
    }
    if (!renormalise(f, p)) return;
    incoming = outgoing;
    if (s.collided) {
      x = x + outgoing * s.distance;
      kind = VertexKind::Medium;
      d = s.densitiesAtEnd;
    } else {
      x = glm::normalize(x + outgoing * segment.length) * medium_.groundRadius();
      kind = VertexKind::Ground;
      d = ConstituentDensities(0.0);
    }
  }
}

}  // namespace firmament::reference
