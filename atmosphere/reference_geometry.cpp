#include "atmosphere/reference_geometry.h"

#include <algorithm>
#include <cmath>

#include "common/atmosphere_lut.glsl"

namespace firmament::reference {

ViewSegment viewSegment(const SpectralMedium& medium, glm::dvec3 camera, glm::dvec3 direction) {
  ViewSegment v;
  v.direction = glm::normalize(direction);
  double r = glm::length(camera);
  const glm::dvec3 up = r > 0.0 ? camera / r : glm::dvec3(0.0, 0.0, 1.0);
  double mu = glm::dot(up, v.direction);
  glm::dvec3 origin = camera;
  if (r > medium.topRadius()) {
    // From space: the ray enters where it first meets the top sphere, if it does.
    // (common/geometry.glsl: rayIntersectsGround and distanceToBottomAtmosphereBoundary work for any
    // sphere the ray starts outside of; here the top sphere.)
    if (!shared::rayIntersectsGround(r, mu, medium.topRadius())) return v;  // not in the atmosphere
    origin = camera + v.direction * shared::distanceToBottomAtmosphereBoundary(r, mu, medium.topRadius());
    r = glm::length(origin);
    mu = glm::dot(origin / r, v.direction);
  }
  // Below the ground: see from just above it (as the GPU does).
  const double raised = std::clamp(r, medium.groundRadius() + kBelowGroundClearance, medium.topRadius());
  if (raised != r) {
    origin = (r > 0.0 ? origin / r : up) * raised;
    r = raised;
    mu = glm::dot(origin / r, v.direction);
  }
  v.inAtmosphere = true;
  v.origin = origin;
  v.segment = segmentToBoundary(medium, r, mu, &v.hitsGround);
  return v;
}

std::vector<double> shadowCrossings(glm::dvec3 origin, glm::dvec3 direction, glm::dvec3 sun, double groundRadius,
                                    double length) {
  // Components perpendicular to the sun axis: x_perp(t) = o_perp + t w_perp. The crossings solve
  //   |o_perp + t w_perp|^2 = R^2  <=>  a t^2 + 2 b t + c = 0,
  //   a = w_perp.w_perp, b = o_perp.w_perp, c = o_perp.o_perp - R^2,
  // with the stable roots q = -(b + sign(b) sqrt(b^2 - a c)), t = q / a and t = c / q.
  const glm::dvec3 oPerp = origin - glm::dot(origin, sun) * sun;
  const glm::dvec3 wPerp = direction - glm::dot(direction, sun) * sun;
  const double a = glm::dot(wPerp, wPerp);
  const double b = glm::dot(oPerp, wPerp);
  const double c = (glm::length(oPerp) - groundRadius) * (glm::length(oPerp) + groundRadius);
  std::vector<double> roots;
  if (a < 1e-30) return roots;  // parallel to the axis: never crosses
  const double disc = b * b - a * c;
  if (disc <= 0.0) return roots;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  for (double t : {q / a, q != 0.0 ? c / q : -1.0})
    if (t > 0.0 && t < length) roots.push_back(t);
  std::sort(roots.begin(), roots.end());
  return roots;
}

glm::dvec3 enuFromZenithAzimuth(double zenith, double azimuth) {
  return {std::sin(zenith) * std::sin(azimuth), std::sin(zenith) * std::cos(azimuth), std::cos(zenith)};
}

void orthonormalBasis(glm::dvec3 n, glm::dvec3* t, glm::dvec3* b) {
  // Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an Orthonormal Basis,
  // Revisited" (JCGT 6(1)).
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double bb = n.x * n.y * a;
  *t = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * bb, -sign * n.x);
  *b = glm::dvec3(bb, sign + n.y * n.y * a, -n.y);
}

}  // namespace firmament::reference
