#include "atmosphere/reference_optical_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/atmosphere_lut.glsl"

namespace firmament::reference {

double RaySegment::radiusAt(double s) const { return shared::radiusAfter(r, mu, s); }

RaySegment segmentToBoundary(const SpectralMedium& medium, double r, double mu, bool* hitsGround) {
  RaySegment segment;
  segment.r = std::clamp(r, medium.groundRadius(), medium.topRadius());
  segment.mu = std::clamp(mu, -1.0, 1.0);
  const bool ground = shared::rayIntersectsGround(medium.geometry(), segment.r, segment.mu);
  segment.length = shared::distanceToNearestAtmosphereBoundary(medium.geometry(), segment.r, segment.mu);
  if (hitsGround) *hitsGround = ground;
  return segment;
}

ColumnIntegrator::ColumnIntegrator(const SpectralMedium& medium, double relativeTolerance)
    : medium_(medium), relativeTolerance_(relativeTolerance) {
  const glm::dvec3 scale = medium.maxExtinctionPerDensity();
  for (int c = 0; c < 3; ++c)
    absoluteFloor_[c] = scale[c] > 0.0 ? kOpticalDepthFloor / scale[c] : std::numeric_limits<double>::infinity();
}

bool ColumnIntegrator::evaluatePanel(const RaySegment& segment, double a, double b,
                                     ConstituentDensities* kronrod) const {
  const GaussKronrod15& rule = gaussKronrod15();
  // ∫_a^b f = h Σ w_k f(c + h x_k), c = (a + b)/2, h = (b - a)/2.
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  glm::dvec3 k(0.0), g(0.0);
  for (int i = 0; i < kKronrodPoints; ++i) {
    const glm::dvec3 d = medium_.densitiesAt(segment.radiusAt(centre + half * rule.nodes[i]));
    k += rule.kronrodWeights[i] * d;
    g += rule.gaussWeights[i] * d;
  }
  k *= half;
  g *= half;
  *kronrod = k;
  for (int c = 0; c < 3; ++c)
    if (std::abs(k[c] - g[c]) > relativeTolerance_ * k[c] + absoluteFloor_[c]) return false;
  return true;
}

int ColumnIntegrator::initialCuts(const RaySegment& segment, double* cuts) const {
  int count = 0;
  cuts[count++] = 0.0;
  // The ray's line meets the sphere of radius R where radiusAfter(r, mu, t) = R: the shared
  // raySphereRoots (common/geometry.glsl), both roots kept when inside (0, length).
  for (double radius : medium_.densityBreakRadii()) {
    double tNear = 0.0, tFar = 0.0;
    if (!shared::raySphereRoots(segment.r, segment.mu, radius, tNear, tFar)) continue;
    for (double t : {tNear, tFar})
      if (t > 0.0 && t < segment.length) cuts[count++] = t;
  }
  cuts[count++] = segment.length;
  std::sort(cuts + 1, cuts + count - 1);
  return count;
}

ConstituentDensities ColumnIntegrator::column(const RaySegment& segment) const {
  ConstituentDensities total(0.0);
  forEachPanel(segment, [&](const ColumnPanel& panel) {
    total = panel.columnBefore + panel.column;
    return true;
  });
  return total;
}

ConstituentDensities ColumnIntegrator::columnOnSubinterval(const RaySegment& segment, double a, double b) const {
  const GaussKronrod15& rule = gaussKronrod15();
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  glm::dvec3 k(0.0);
  for (int i = 0; i < kKronrodPoints; ++i)
    k += rule.kronrodWeights[i] * medium_.densitiesAt(segment.radiusAt(centre + half * rule.nodes[i]));
  return half * k;
}

bool ColumnIntegrator::columnToSun(double r, double muSun, ConstituentDensities* column) const {
  const double rc = std::clamp(r, medium_.groundRadius(), medium_.topRadius());
  // The ray toward the sun's centre leaves through the ground (planet shadow) or the top.
  if (shared::rayIntersectsGround(medium_.geometry(), rc, muSun)) {
    *column = ConstituentDensities(0.0);
    return false;
  }
  RaySegment segment{rc, std::clamp(muSun, -1.0, 1.0),
                     shared::distanceToTopAtmosphereBoundary(medium_.geometry(), rc, std::clamp(muSun, -1.0, 1.0))};
  *column = this->column(segment);
  return true;
}

FreePathSample sampleFreePath(const ColumnIntegrator& integrator, const RaySegment& segment, glm::dvec3 weights,
                              double targetOpticalDepth) {
  FreePathSample result;
  result.distance = segment.length;
  integrator.forEachPanel(segment, [&](const ColumnPanel& panel) {
    const double tauBefore = glm::dot(weights, panel.columnBefore);
    const double tauPanel = glm::dot(weights, panel.column);
    if (tauBefore + tauPanel < targetOpticalDepth) {
      result.columnBefore = panel.columnBefore + panel.column;
      return true;  // not in this panel
    }
    // Solve g(t) = tauBefore + dot(weights, D(start, t)) - target = 0 on [start, end]; g is
    // increasing with g' = dot(weights, d(t)) >= 0. Newton from the linear guess, kept inside a
    // shrinking bracket (bisection when a step leaves it).
    const double needed = targetOpticalDepth - tauBefore;
    double lo = panel.start, hi = panel.end;
    double t = panel.start + (panel.end - panel.start) * std::clamp(needed / std::max(tauPanel, 1e-300), 0.0, 1.0);
    ConstituentDensities partial(0.0);
    for (int iteration = 0; iteration < 60; ++iteration) {
      partial = integrator.columnOnSubinterval(segment, panel.start, t);
      const double g = glm::dot(weights, partial) - needed;
      if (g > 0.0)
        hi = t;
      else
        lo = t;
      if (std::abs(g) <= 1e-13 * std::max(targetOpticalDepth, 1e-300) || hi - lo <= 1e-9 * std::max(1.0, hi)) break;
      const double slope = glm::dot(weights, integrator.medium().densitiesAt(segment.radiusAt(t)));
      double next = slope > 0.0 ? t - g / slope : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      t = next;
    }
    result.collided = true;
    result.distance = t;
    result.columnBefore = panel.columnBefore + partial;
    result.densitiesAtEnd = integrator.medium().densitiesAt(segment.radiusAt(t));
    return false;
  });
  return result;
}

}  // namespace firmament::reference
