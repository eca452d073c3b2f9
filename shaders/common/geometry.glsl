// geometry.glsl: rays against spheres centred on the planet, for the atmosphere and cloud shells.
// Shared with C++ (double) by the rules of compat.glsl; tests/gpu/test_shared_functions.cpp checks the
// float GPU results against the double CPU ones.
//
// A ray starts at distance r from the planet centre with mu = cos(view zenith angle) = dot(direction,
// up). The point at distance t along it has radius sqrt(r² + 2 r mu t + t²), so the ray meets the
// sphere of radius R where
//     t² + 2 b t + c = 0,   b = r mu,   c = r² − R² = (r − R)(r + R),
//     t = −b ± √Δ,          Δ = b² − c = (r mu)² + (R − r)(R + r).
// Float has 24 bits; r² ≈ 4e13 m² carries an error of ~2.4e6 m², larger than the whole R² − r² of a
// ray 1 m below the top of the atmosphere. Hence, throughout:
//   - Δ as (R − r)(R + r) + (r mu)², never r²(mu² − 1) + R²: R − r is exact for radii within a factor
//     2 of each other (Sterbenz), so the altitude difference survives;
//   - the root that would be a difference of near-equal numbers (−b + √Δ with b > 0, or −b − √Δ with
//     b < 0) comes from the product of the roots, t₀ t₁ = c, instead: q = −(b + sign(b) √Δ) is a sum of
//     same-signed terms, and the roots are q and c / q.
#ifndef FIRMAMENT_GEOMETRY_GLSL
#define FIRMAMENT_GEOMETRY_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// Δ (a quarter of the textbook b² − 4ac, for the half-b form above); ≥ 0 iff the ray's line meets the
// sphere. Not clamped: its sign is the answer to "does it hit".
SHARED_INLINE Real sphereDiscriminant(Real r, Real mu, Real radius) {
  Real rmu = r * mu;
  return (radius - r) * (radius + r) + rmu * rmu;
}

// Both signed distances tNear ≤ tFar at which the ray's line crosses the sphere (negative = behind the
// start); false, with both 0, when it misses. Each root is formed without cancellation (see top).
SHARED_INLINE bool raySphereRoots(Real r, Real mu, Real radius, OUT(Real) tNear, OUT(Real) tFar) {
  Real b = r * mu;
  Real c = (r - radius) * (r + radius);
  Real discriminant = (radius - r) * (radius + r) + b * b;
  tNear = 0.0;
  tFar = 0.0;
  if (discriminant < 0.0) return false;
  Real s = sqrt(discriminant);
  if (b <= 0.0) {
    tFar = s - b;                              // q = −b + √Δ ≥ 0: both terms ≥ 0
    tNear = tFar > 0.0 ? c / tFar : 0.0;       // c / q; tFar = 0 only when b = Δ = c = 0
  } else {
    tNear = -(b + s);                          // q = −(b + √Δ) < 0
    tFar = c / tNear;
  }
  return true;
}

// Bruneton 2017, DistanceToTopAtmosphereBoundary: distance from inside (r ≤ topRadius) to where the
// ray leaves the sphere, the far root. Δ ≥ (R − r)(R + r) ≥ 0 inside; the clamp absorbs rounding
// for r a hair above the top. Looking up (b > 0) the far root is c / q = (R² − r²) / (r mu + √Δ),
// which stays accurate when r is close to R (−b + √Δ would cancel there).
SHARED_INLINE Real distanceToTopAtmosphereBoundary(Real r, Real mu, Real topRadius) {
  Real b = r * mu;
  Real s = sqrt(max(sphereDiscriminant(r, mu, topRadius), 0.0));
  Real exitDistance = b <= 0.0 ? s - b : (topRadius - r) * (topRadius + r) / (b + s);
  return max(exitDistance, 0.0);
}

// Bruneton 2017, DistanceToBottomAtmosphereBoundary: distance from above the ground (r ≥
// bottomRadius) to the ground, the near root, meaningful when rayIntersectsGround. Looking down
// (b < 0) it is c / q = (r² − Rb²) / (−r mu + √Δ): for a grazing ray −r mu ≈ √Δ and the textbook
// −r mu − √Δ would lose every digit. Looking up the near root is behind: 0.
SHARED_INLINE Real distanceToBottomAtmosphereBoundary(Real r, Real mu, Real bottomRadius) {
  Real b = r * mu;
  if (b >= 0.0) return 0.0;
  Real s = sqrt(max(sphereDiscriminant(r, mu, bottomRadius), 0.0));
  return max((r - bottomRadius) * (r + bottomRadius) / (s - b), 0.0);
}

// Bruneton 2017, RayIntersectsGround: looking down, and the line meets the ground sphere.
SHARED_INLINE bool rayIntersectsGround(Real r, Real mu, Real bottomRadius) {
  return mu < 0.0 && sphereDiscriminant(r, mu, bottomRadius) >= 0.0;
}

// Bruneton 2017, DistanceToNearestAtmosphereBoundary: the ground if the ray hits it, else the top.
SHARED_INLINE Real distanceToNearestAtmosphereBoundary(Real r, Real mu, Real bottomRadius, Real topRadius,
                                         bool intersectsGround) {
  return intersectsGround ? distanceToBottomAtmosphereBoundary(r, mu, bottomRadius)
                          : distanceToTopAtmosphereBoundary(r, mu, topRadius);
}

// The first stretch [tEnter, tExit] (0 ≤ tEnter ≤ tExit) of the ray inside the shell
// innerRadius ≤ radius ≤ outerRadius, e.g. a cloud layer; false if the ray never enters it ahead.
// From above the shell, a ray can cross it, pass over the inner sphere and cross it again: this is the
// first crossing (march again from tExit for the second).
SHARED_INLINE bool rayShellSegment(Real r, Real mu, Real innerRadius, Real outerRadius, OUT(Real) tEnter, OUT(Real) tExit) {
  Real outerNear;
  Real outerFar;
  Real innerNear;
  Real innerFar;
  bool hitsOuter = raySphereRoots(r, mu, outerRadius, outerNear, outerFar);
  bool hitsInner = raySphereRoots(r, mu, innerRadius, innerNear, innerFar);
  tEnter = 0.0;
  tExit = 0.0;
  if (!hitsOuter || outerFar < 0.0) return false;  // the shell is missed or behind
  if (r > outerRadius) {
    // Above: c > 0, so both outer roots are ahead. Leave through the inner sphere if it is hit.
    tEnter = outerNear;
    tExit = hitsInner && innerNear >= 0.0 ? innerNear : outerFar;
  } else if (r >= innerRadius) {
    // Inside the shell: inner roots share a sign (c ≥ 0); both ahead when looking down at it.
    tEnter = 0.0;
    tExit = hitsInner && innerNear >= 0.0 ? innerNear : outerFar;
  } else {
    // Below (inside the inner sphere): c < 0 for both spheres, so each far root is ahead.
    tEnter = innerFar;
    tExit = outerFar;
  }
  return tExit > tEnter;
}

// r and mu of a ray from `origin` (planet-centred, metres) along the unit vector `direction`.
SHARED_INLINE void rayRadiusAndCosine(vec3 origin, vec3 direction, OUT(Real) r, OUT(Real) mu) {
  r = length(origin);
  mu = r > 0.0 ? clamp(dot(origin, direction) / r, -1.0, 1.0) : 1.0;
}

SHARED_END

#endif  // FIRMAMENT_GEOMETRY_GLSL
