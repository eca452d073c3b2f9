#pragma once
// Geometry of one view ray in the planet-centred frame for the reference (docs/reference.md):
// where it enters and leaves the atmosphere, and where it crosses the edge of the planet's shadow.
#include <glm/glm.hpp>
#include <vector>

#include "atmosphere/reference_optical_depth.h"

namespace firmament::reference {

// Cameras below the ground sphere see from just above it, as the GPU path does:
// r = max(r, ground radius + kBelowGroundClearance).
inline constexpr double kBelowGroundClearance = 0.01;  // m

struct ViewSegment {
  bool inAtmosphere = false;  // false: the ray never enters the atmosphere (camera in space)
  bool hitsGround = false;    // the segment ends on the ground sphere (else at the top)
  glm::dvec3 origin{0.0};     // planet-centred, m: the camera, or where the ray enters the top
  glm::dvec3 direction{0.0, 0.0, 1.0};
  RaySegment segment;  // (r, mu, length) of origin along direction
};

// camera: planet-centred position (m); direction: unit. A camera above the top radius first
// travels to the top sphere (the shared distanceToSphereNear); below the ground it is raised to
// ground + kBelowGroundClearance along its own vertical.
ViewSegment viewSegment(const SpectralMedium& medium, glm::dvec3 camera, glm::dvec3 direction);

// Distances t in (0, length) where origin + t direction crosses the boundary of the planet's
// shadow for a point sun in direction sun: the cylinder of the ground radius around the sun axis,
// |x - (x.s) s| = R_ground (on the night side x.s < 0; crossings on the day side are returned too,
// harmlessly). Sorted. The shadow test itself is shared::rayIntersectsGround(r, mu_s).
std::vector<double> shadowCrossings(glm::dvec3 origin, glm::dvec3 direction, glm::dvec3 sun, double groundRadius,
                                    double length);

// Unit vector (East, North, Up) for a zenith angle and an azimuth clockwise from north (rad).
glm::dvec3 enuFromZenithAzimuth(double zenith, double azimuth);

// Two unit vectors completing `n` (unit) to an orthonormal basis (Duff et al. 2017).
void orthonormalBasis(glm::dvec3 n, glm::dvec3* t, glm::dvec3* b);

}  // namespace firmament::reference
