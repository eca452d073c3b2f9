#pragma once
// Density columns (hence optical depths at every wavelength) along straight segments in the
// spherical atmosphere, by adaptive Gauss–Kronrod quadrature in double; the transmittance toward
// the sun; and free-path sampling by inverting the optical depth (docs/reference.md).
//
// A segment starts at radius r (m from the planet centre) with direction cosine mu (to the local
// zenith) and has a length (m); the radius after a distance s is the shared radiusAfter(r, mu, s)
// (law of cosines). Its density column is
//   D(a, b) = ∫_a^b (d_R, d_M, d_O)(radiusAfter(r, mu, s)) ds        (m; see reference_medium.h)
// and the optical depth at wavelength i is tau_i = dot(extinctionPerDensity(i), D).
#include <glm/glm.hpp>
#include <vector>

#include "atmosphere/reference_medium.h"
#include "atmosphere/reference_quadrature.h"

namespace firmament::reference {

struct RaySegment {
  double r = 0.0;       // m, start radius
  double mu = 1.0;      // cosine of the direction's zenith angle at the start
  double length = 0.0;  // m
  double radiusAt(double s) const;
};

// The segment from radius r along mu to the nearest boundary of the atmosphere (ground or top), the
// shared distanceToNearestAtmosphereBoundary. r is clamped into [ground, top] first (a point on a
// boundary up to rounding). `hitsGround` tells which boundary ends it.
RaySegment segmentToBoundary(const SpectralMedium& medium, double r, double mu, bool* hitsGround);

// One accepted quadrature panel [start, end] of a segment, in order along it.
struct ColumnPanel {
  double start = 0.0;
  double end = 0.0;
  ConstituentDensities columnBefore{0.0};  // D(0, start)
  ConstituentDensities column{0.0};        // D(start, end), the K15 estimate
};

// Adaptive Gauss–Kronrod on the density vector. A panel is accepted when, for each constituent c,
//   |K15_c - G7_c| <= relativeTolerance * K15_c + kOpticalDepthFloor / max_i beta_c(i),
// i.e. every wavelength's optical depth on the panel is known to the relative tolerance, or to an
// absolute 1e-13 where the panel's contribution is smaller than that. Bisection, depth first and
// left first, so panels come out in order along the segment and the column before each one is exact
// to the tolerance.
class ColumnIntegrator {
 public:
  static constexpr double kOpticalDepthFloor = 1e-13;
  static constexpr int kMaxDepth = 48;

  ColumnIntegrator(const SpectralMedium& medium, double relativeTolerance);

  // Calls visit(const ColumnPanel&) for each accepted panel in order; visit returns false to stop.
  template <class Visit>
  void forEachPanel(const RaySegment& segment, Visit&& visit) const;

  ConstituentDensities column(const RaySegment& segment) const;

  // Distances in (0, length) where the segment crosses a density break radius
  // (SpectralMedium::densityBreakRadii), sorted, with 0 and length added at the ends: the initial
  // panels of the adaptive quadrature.
  // Writes at most kMaxCuts values and returns the count.
  static constexpr int kMaxCuts = 2 * SpectralMedium::kMaxDensityBreaks + 2;
  int initialCuts(const RaySegment& segment, double* cuts) const;
  // K15 on [a, b] of the segment, no adaptivity: accurate inside an accepted panel.
  ConstituentDensities columnOnSubinterval(const RaySegment& segment, double a, double b) const;

  // Column from radius r toward the sun (cosine muSun) to the top of the atmosphere; false when the
  // ground hides the sun (the sun as a point: the ray toward its centre meets the ground sphere).
  bool columnToSun(double r, double muSun, ConstituentDensities* column) const;

  const SpectralMedium& medium() const { return medium_; }
  double relativeTolerance() const { return relativeTolerance_; }

 private:
  // K15 and G7 over [a, b]; returns true when the panel is accepted.
  bool evaluatePanel(const RaySegment& segment, double a, double b, ConstituentDensities* kronrod) const;

  const SpectralMedium& medium_;
  double relativeTolerance_;
  glm::dvec3 absoluteFloor_;  // per constituent, m (density column)
};

// Free-path sampling along a segment by inverting the optical depth of one weighting of the
// constituents (the hero wavelength's extinctionPerDensity): finds the distance t where
// dot(weights, D(0, t)) = targetOpticalDepth, or reports that the segment's total is smaller.
struct FreePathSample {
  bool collided = false;
  double distance = 0.0;                     // t (collided) or the segment length
  ConstituentDensities columnBefore{0.0};    // D(0, t), or D(0, length) when it did not collide
  ConstituentDensities densitiesAtEnd{0.0};  // (d_R, d_M, d_O) at t when collided
};

FreePathSample sampleFreePath(const ColumnIntegrator& integrator, const RaySegment& segment, glm::dvec3 weights,
                              double targetOpticalDepth);

// ---------------------------------------------------------------------------------------------

template <class Visit>
void ColumnIntegrator::forEachPanel(const RaySegment& segment, Visit&& visit) const {
  if (!(segment.length > 0.0)) return;
  // Explicit stack of pending intervals; the leftmost pending interval is on top. Bisection adds
  // at most one entry per level above the initial panels.
  struct Pending {
    double a, b;
    int depth;
  };
  double cuts[kMaxCuts];
  const int cutCount = initialCuts(segment, cuts);
  Pending stack[kMaxCuts + kMaxDepth + 2];
  int top = 0;
  for (int i = cutCount - 1; i > 0; --i) stack[top++] = {cuts[i - 1], cuts[i], 0};
  ConstituentDensities before(0.0);
  while (top > 0) {
    const Pending p = stack[--top];
    ConstituentDensities k;
    const bool accepted = evaluatePanel(segment, p.a, p.b, &k);
    if (accepted || p.depth >= kMaxDepth) {
      ColumnPanel panel{p.a, p.b, before, k};
      before += k;
      if (!visit(static_cast<const ColumnPanel&>(panel))) return;
      continue;
    }
    const double m = 0.5 * (p.a + p.b);
    stack[top++] = {m, p.b, p.depth + 1};  // right half visited after the left
    stack[top++] = {p.a, m, p.depth + 1};
  }
}

}  // namespace firmament::reference
