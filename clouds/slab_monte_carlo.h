// The case the octave model's diffusion floor is derived for, solved by Monte Carlo: a homogeneous,
// conservatively scattering, plane-parallel slab lit by the sun, the default dual Henyey-Greenstein
// phase (CloudLightingSettings), black below, no diffuse light from above. The floor's checks count the
// light of scattering orders >= 2 (the octaves' first term carries order 1); the deck's transmission
// (cloudSlabTransmission) the photons of orders >= 1. Beside it, the floor as
// the march evaluates it in that slab (common/cloud_lighting.glsl), so that the two can be compared:
// tests/clouds/test_cloud_floor_monte_carlo.cpp and test_cloud_deck_transmission.cpp check a few cases,
// `bench_floor_slab` prints the sweeps the floor's corrections were fitted to (docs/clouds.md "Lighting", item 6).
//
// Cut to a vertical cylinder (an optical radius; infinite by default, the slab), it is a finite cloud: the
// light that leaves through the sides, which the column-wise floor does not see, measured
// (`bench_floor_slab` part 4).
//
// Depths are optical (0 at the top); directions are propagation directions with z pointing down; the sun's
// light travels towards +x, so the cylinder's sunlit side is at -x. Horizontal positions are optical too.
#pragma once

#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace firmament {

struct SlabDirection {
  double x, y, z;
};

// A point in the medium: x, y optical distances from the cylinder's axis, z optical depth below the top.
struct SlabPoint {
  double x, y, z;
};

struct SlabEstimate {
  double mean = 0.0;
  double standardError = 0.0;
};

// Light scattered out of the slab's base by photons followed from the sun.
struct SlabPhotonResult {
  SlabEstimate flux;                   // per unit flux mu0 E entering the top
  std::vector<SlabEstimate> radiance;  // per unit solar irradiance E, per exit-cosine bin [i / n, (i + 1) / n)
};

class SlabMonteCarlo {
 public:
  // radius: the cylinder's optical radius (infinite: the plane-parallel slab).
  SlabMonteCarlo(double thickness, double mu0, uint64_t seed, double radius = std::numeric_limits<double>::infinity());

  // The source at depth tau (on the axis) scattered into `out`: integral of p(w . out) L(w) dw over the
  // diffuse radiance L (per unit solar irradiance, per sr). Backward paths, the sun added at each vertex.
  SlabEstimate source(double tau, SlabDirection out, int paths);
  // The same at any point of the medium.
  SlabEstimate source(SlabPoint at, SlabDirection out, int paths);
  // The radiance leaving the base along `out` (out.z > 0) at the axis, by the same backward paths.
  SlabEstimate baseRadiance(SlabDirection out, int paths);
  // Photons from the sun, binned by the cosine of their exit from the base: quiet at a low sun, where a
  // backward path that climbs to the top picks up e^(-tau/mu0) rarely and strongly. Counted from
  // scattering order minOrder on (2: the floor's light; 1: all the diffuse light; 0: the direct beam too).
  // The slab only: the photons enter the whole top, and a finite radius is not used.
  SlabPhotonResult photonsThroughBase(int photons, int bins, int minOrder = 2);

 private:
  double walk(SlabPoint p, SlabDirection w, bool countFirst);
  bool inside(SlabPoint p) const;
  // The optical distance from p to where the sun's ray into p entered the medium.
  double opticalDepthToSun(SlabPoint p) const;

  double thickness_, mu0_, radius_;
  SlabDirection sun_;
  std::mt19937_64 rng_;
};

// A direction leaving at muDown = cosine with the downward vertical (azimuth in degrees from the sun's).
SlabDirection slabDirection(double muDown, double azimuth_deg = 0.0);

// The floor (weight 1) as the march evaluates it in the slab: the escape function's correction times the
// Eddington source, at depth tau, for light scattered at muDown (without the low-sun factor).
double slabFloorSource(double mu0, double tau, double thickness, double muDown);
// Its radiance leaving the base at muDown > 0, with or without the base's limb darkening.
double slabFloorBaseRadiance(double mu0, double thickness, double muDown, bool limb);
// Its flux out of the base per unit flux mu0 E (with the limb darkening, without the low-sun factor).
double slabFloorBaseFlux(double thickness, double mu0);

}  // namespace firmament
