#pragma once
// Monte Carlo path tracer for scattering orders >= 2 (docs/reference.md, "Orders >= 2").
//
// Paths start at the camera and end at the sun by next-event estimation (the sun is a point source
// for in-scattering, as in the deterministic order 1). Orders 0 and 1 are left to the deterministic
// integrator: no next-event estimation at the first vertex.
//
// Spectral sampling: one hero wavelength h per path, chosen uniformly among the N; the path's free
// paths and scattering directions are sampled as for h, and the contribution at every wavelength
// lambda is weighted by one-sample multiple importance sampling over the N techniques with the
// balance heuristic (Wilkie et al. 2014, "Hero wavelength spectral sampling"):
//   F(lambda) = f_lambda(x) / ( (1/N) Σ_j p_j(x) ),
// f_lambda the path's measurement contribution at lambda and p_j its density had j been the hero.
// Every factor of f and of each p_j is tracked along the path, so this estimator is unbiased at every
// wavelength and never worse than N times the single-wavelength estimator.
//
// Per path vertex:
//   free flight:  f_lambda *= T_lambda(segment)                p_j *= T_j(segment) sigma_t,j(x)
//                 (reaching the ground instead:  f *= T,  p_j *= T_j: the probability of no collision)
//   next event:   add f_lambda / pbar * S_lambda(nu_sun) E_lambda T_sun,lambda(x)          (medium)
//                 add f_lambda / pbar * a_lambda / pi mu_s E_lambda T_sun,lambda(x)      (ground)
//   new direction: medium: f_lambda *= S_lambda(nu) = sigma_R p_R(nu) + sigma_M p_CS(nu),
//                          p_j *= P_R,j p_R(nu) + (1 - P_R,j) p_HG(nu), P_R,j = sigma_R,j / sigma_s,j
//                  (Rayleigh sampled exactly, Cornette–Shanks through Henyey–Greenstein with the same g)
//                  ground: cosine-weighted, f_lambda *= a_lambda cos/pi, p_j *= cos/pi.
// The first segment, along the view ray, is sampled conditioned on a collision inside it
// (p_j = sigma_t,j T_j(0, t) / (1 - T_j(0, D))), and, when the view ray meets the ground, a second
// path starts on the ground with f = T(0, D): every sample explores both. The next segments up to
// forcedSegments that would leave through the top are also sampled conditioned on colliding (a
// path that escapes early carries no light, and orders 2 and 3 dominate the sky's multiple
// scattering); later ones by plain free-path sampling, so paths end by escaping.
#include <glm/glm.hpp>
#include <vector>

#include "atmosphere/reference_geometry.h"
#include "atmosphere/reference_optical_depth.h"
#include "atmosphere/reference_random.h"

namespace firmament::reference {

struct PathTracerSettings {
  double opticalDepthTolerance = 1e-6;  // relative, of every density column the tracer integrates
  int maxBounces = 1000;                // scattering + reflection events per path (hard cap)
  int rouletteStartBounce = 100;        // Russian roulette only from this event on
  int forcedSegments = 3;               // segments (the view ray included) sampled conditioned on a collision
};

// The view ray, prepared once per pixel and shared by all its samples.
struct PreparedViewRay {
  ViewSegment view;
  std::vector<ColumnPanel> panels;   // of the view segment, in order
  ConstituentDensities column{0.0};  // D(0, length)
};

class PathTracer {
 public:
  PathTracer(const SpectralMedium& medium, glm::dvec3 sunDirection, const PathTracerSettings& settings);

  PreparedViewRay prepare(const ViewSegment& view) const;

  // One sample of the radiance of orders >= 2 at every wavelength (W m^-2 sr^-1 nm^-1), written to
  // `contribution` (size N, overwritten). Uses `random` only.
  void sample(const PreparedViewRay& ray, Random& random, std::vector<double>& contribution) const;

  struct PathStatistics {
    long long paths = 0;
    long long events = 0;  // scattering + ground events
    int longestPath = 0;
    long long rouletteKills = 0;
    long long capped = 0;  // paths stopped by maxBounces
  };
  // Counts of the calling thread's paths since the last reset (thread_local).
  static PathStatistics& threadStatistics();

 private:
  enum class VertexKind { Medium, Ground };
  // Continues a path from vertex x (already in f, p); adds its next-event contributions.
  void continuePath(glm::dvec3 x, glm::dvec3 incoming, VertexKind kind, ConstituentDensities densities, int hero,
                    std::vector<double>& f, std::vector<double>& p, Random& random,
                    std::vector<double>& contribution) const;
  // Collision on `segment` for the hero, conditioned on one happening (forced) or not.
  FreePathSample sampleSegment(const RaySegment& segment, int hero, bool forced, double u,
                               ConstituentDensities* segmentColumn) const;
  void nextEvent(glm::dvec3 x, glm::dvec3 incoming, VertexKind kind, ConstituentDensities densities,
                 const std::vector<double>& f, std::vector<double>& contribution) const;

  const SpectralMedium& medium_;
  glm::dvec3 sun_;
  PathTracerSettings settings_;
  ColumnIntegrator columns_;
};

// Phase-function sampling (cosine nu of the angle to the incoming propagation direction).
double sampleRayleighCosine(double u);                    // pdf 3/8 (1 + nu^2) over nu in [-1, 1]
double sampleHenyeyGreensteinCosine(double g, double u);  // pdf 2 pi p_HG(g, nu)

}  // namespace firmament::reference
