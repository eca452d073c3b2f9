// bench_floor_slab [paths photons azimuth_deg parts]   (parts: which of 1-5 to run, default "12345")
// The diffusion floor (and the deck transmission built on it) against Monte Carlos of a homogeneous conservative slab
// (clouds/slab_monte_carlo.h): the sweeps its two corrections were fitted to (docs/clouds/multiple-scattering.md, item
// 6). CPU only.
//   1. The radiance leaving the base (backward paths, `paths` per angle, default 100000; exit azimuth
//      `azimuth_deg` from the sun's, default 90): floor / Monte Carlo at exit cosines mu 1 .. 0.05, without and with
//      the base's limb darkening (cloudBaseLimbFactor), for optical thickness 10, 20 and mu0 0.3, 0.64, 1.
//   2. The light leaving the base from photons (`photons` per case, default 2000000), binned by exit
//      cosine: floor / Monte Carlo averaged over the bins mu >= 0.1 (weighted by their photons), without
//      and with the low-sun factor (cloudFloorLowSunFactor), for thickness 10, 20, 40 and mu0 0.087 .. 1.
//   3. The deck's transmission (cloudSlabTransmission): the diffuse flux out of the base from
//      photons of orders >= 1 (`photons` / 10 per case) against the Eddington form's diffuse part and
//      against cloudSlabTransmission's, for vertical optical depth 1-40 and mu0 0.087 .. 1.
//   4. A finite cloud: the same medium cut to a vertical cylinder of optical radius R, R / H
//      0.5, 1, 2 and infinite (thickness H 10 and 20, mu0 1 and 0.64), the source of orders >= 2 (backward
//      paths, `paths` / 4 per point) against the slab's floor at the same depth, which is what the
//      column-wise floor gives inside any cylinder: on the axis at depths 0.25, 0.5, 0.9 H, scattered
//      down and up, and across the cylinder at mid-depth (x / R -0.75 .. 0.75, the sunlit side negative).
//   5. The octaves' form in a slab: the light of orders >= 2 that the march gives a sample of a
//      homogeneous slab (its octaves i >= 1, the floor, and the larger of the two, which the march takes;
//      without the reflected light, cloudReflectedSource, which the march adds on top of the larger), with
//      each type's shipped constants (cumulus, stratocumulus), against the Monte Carlo's source (backward paths,
//      `paths` / 5 per point), thickness 0.5-20, mu0 1 and 0.5, at mid-depth and 0.9 H, scattered down,
//      sideways and up (azimuth 90 deg from the sun's).
// Each figure is printed with the Monte Carlo's standard error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "clouds/cloud_settings.h"
#include "clouds/slab_monte_carlo.h"
#include "common/cloud_lighting.glsl"

using namespace firmament;

int main(int argc, char** argv) {
  const int paths = argc > 1 ? std::atoi(argv[1]) : 100000;
  const int photons = argc > 2 ? std::atoi(argv[2]) : 2000000;
  const double azimuth_deg = argc > 3 ? std::atof(argv[3]) : 90.0;
  const char* parts = argc > 4 ? argv[4] : "12345";
  auto runs = [&](char part) { return std::strchr(parts, part) != nullptr; };
  if (paths < 100 || photons < 1000) {
    std::fprintf(stderr, "bench_floor_slab: paths (>= 100) and photons (>= 1000) expected, got %d and %d\n", paths,
                 photons);
    return 2;
  }

  if (runs('1')) {
    std::printf(
        "1. radiance leaving the base, floor / Monte Carlo (without -> with the limb darkening), %d paths per angle, "
        "azimuth %.0f deg\n",
        paths, azimuth_deg);
    const double exits[] = {1.0, 0.7, 0.5, 0.35, 0.25, 0.15, 0.1, 0.05};
    for (double thickness : {10.0, 20.0})
      for (double mu0 : {0.3, 0.64, 1.0}) {
        SlabMonteCarlo slab(thickness, mu0, uint64_t(1000 * thickness + 100 * mu0));
        std::printf("thickness %2.0f mu0 %.2f:", thickness, mu0);
        for (double mu : exits) {
          const SlabEstimate mc = slab.baseRadiance(slabDirection(mu, azimuth_deg), paths);
          std::printf("  mu %.2f %.3f -> %.3f (+-%.3f)", mu, slabFloorBaseRadiance(mu0, thickness, mu, false) / mc.mean,
                      slabFloorBaseRadiance(mu0, thickness, mu, true) / mc.mean, mc.standardError / mc.mean);
        }
        std::printf("\n");
      }
  }

  if (runs('2')) {
    std::printf(
        "2. light leaving the base over mu >= 0.1, floor / photons (without -> with the low-sun factor), %d photons "
        "per case\n",
        photons);
    const int bins = 10;
    for (double thickness : {10.0, 20.0, 40.0})
      for (double mu0 : {0.087, 0.15, 0.2, 0.3, 0.45, 0.64, 1.0}) {
        SlabMonteCarlo slab(thickness, mu0, uint64_t(7000 + 1000 * thickness + 100 * mu0));
        const SlabPhotonResult mc = slab.photonsThroughBase(photons, bins);
        // Ratio over the bins from mu = 0.1 up, each the floor's radiance averaged over the bin (4 cosines,
        // weighted by mu) against the photons', combined with the photons' counts as weights.
        double floorSum = 0.0, mcSum = 0.0, variance = 0.0;
        for (int b = 1; b < bins; ++b) {
          double num = 0.0, den = 0.0;
          for (int k = 0; k < 4; ++k) {
            const double mu = (b + (k + 0.5) / 4.0) / bins;
            num += slabFloorBaseRadiance(mu0, thickness, mu, true) * mu;
            den += mu;
          }
          const double weight =
              (double(b + 1) * (b + 1) - double(b) * b);  // the bin's projected solid angle, x pi / bins^2
          floorSum += weight * num / den;
          mcSum += weight * mc.radiance[size_t(b)].mean;
          variance += weight * weight * mc.radiance[size_t(b)].standardError * mc.radiance[size_t(b)].standardError;
        }
        const double ratio = floorSum / mcSum, factor = shared::cloudFloorLowSunFactor(mu0);
        std::printf("thickness %2.0f mu0 %.3f: %.3f -> %.3f (+-%.3f); flux out of the base %.5f\n", thickness, mu0,
                    ratio, ratio * factor, std::sqrt(variance) / mcSum, mc.flux.mean);
      }
  }

  if (runs('3')) {
    const int deckPhotons = std::max(photons / 10, 1000);
    std::printf(
        "3. the deck's diffuse transmission, Eddington / photons -> cloudSlabTransmission / photons, %d photons per "
        "case\n",
        deckPhotons);
    const CloudLightingSettings lighting;  // the phase SlabMonteCarlo samples
    const double g =
        shared::cloudPhaseMeanCosine(lighting.gForward, lighting.gBack, lighting.backWeight, lighting.alpha);
    for (double depth : {1.0, 2.0, 5.0, 10.0, 20.0, 40.0}) {
      std::printf("depth %2.0f:", depth);
      for (double mu0 : {0.087, 0.15, 0.3, 0.5, 0.7, 1.0}) {
        SlabMonteCarlo slab(depth, mu0, uint64_t(99 + 1000 * depth + 100 * mu0));
        const SlabEstimate mc = slab.photonsThroughBase(deckPhotons, 1, 1).flux;
        const double direct = std::exp(-depth / mu0);
        const double eddington = std::min(shared::cloudEddingtonTransmission(mu0, depth, g), 1.0) - direct;
        const double deck = shared::cloudSlabTransmission(depth / mu0, mu0, g) - direct;
        std::printf("  mu0 %.3f %.3f -> %.3f (+-%.3f)", mu0, eddington / mc.mean, deck / mc.mean,
                    mc.standardError / mc.mean);
      }
      std::printf("\n");
    }
  }

  if (runs('4')) {
    const int pointPaths = std::max(paths / 4, 100);
    std::printf(
        "4. a finite cloud: source of orders >= 2 in a cylinder / the slab's floor at the same depth (+- standard "
        "error), %d paths per point\n",
        pointPaths);
    const double down = 1.0, upward = -1.0;
    for (double thickness : {10.0, 20.0})
      for (double mu0 : {1.0, 0.64})
        for (double aspect : {0.5, 1.0, 2.0, -1.0}) {
          const double radius = aspect > 0.0 ? aspect * thickness : std::numeric_limits<double>::infinity();
          SlabMonteCarlo cloud(thickness, mu0, uint64_t(4000 + 1000 * thickness + 100 * mu0 + 10 * aspect), radius);
          if (aspect > 0.0)
            std::printf("H %2.0f mu0 %.2f R/H %-3g:", thickness, mu0, aspect);
          else
            std::printf("H %2.0f mu0 %.2f R/H inf:", thickness, mu0);
          auto ratio = [&](SlabPoint at, double muDown) {
            const SlabEstimate mc = cloud.source(at, slabDirection(muDown, 90.0), pointPaths);
            std::printf(" %.3f(%.3f)", slabFloorSource(mu0, at.z, thickness, muDown) / mc.mean,
                        mc.standardError / mc.mean);
          };
          std::printf(" axis z/H 0.25 0.5 0.9 down");
          for (double f : {0.25, 0.5, 0.9}) ratio({0.0, 0.0, f * thickness}, down);
          std::printf(" | up");
          for (double f : {0.25, 0.5, 0.9}) ratio({0.0, 0.0, f * thickness}, upward);
          if (aspect > 0.0) {
            std::printf(" | mid-depth x/R -0.75 -0.5 0.5 0.75 sideways");
            for (double f : {-0.75, -0.5, 0.5, 0.75}) ratio({f * radius, 0.0, 0.5 * thickness}, 0.0);
          }
          std::printf("\n");
        }
  }

  if (runs('5')) {
    const int pointPaths = std::max(paths / 5, 100);
    const CloudLightingSettings lighting;
    const double g =
        shared::cloudPhaseMeanCosine(lighting.gForward, lighting.gBack, lighting.backWeight, lighting.alpha);
    for (int kind : {shared::kCloudCumulus, shared::kCloudStratocumulus}) {
      const CloudMultipleScattering ms = cloudTypeMultipleScattering(kind);
      std::printf(
          "5. %s (a %.3f b %.3f c %.3f d %.3f; reflected light r %.3f not included): march / Monte Carlo, octaves i >= "
          "1 | floor | "
          "the larger, %d paths per point\n",
          cloudKindName(kind), ms.a, ms.b, ms.c, ms.d, ms.r, pointPaths);
      const double weightScale = shared::cloudOctaveWeightScale(ms.b, 3);
      for (double thickness : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0})
        for (double mu0 : {1.0, 0.5}) {
          SlabMonteCarlo slab(thickness, mu0, uint64_t(11 + 100 * thickness + 10 * mu0));
          std::printf("H %4.1f mu0 %.1f:", thickness, mu0);
          for (double depth : {0.5, 0.9})
            for (double muDown : {1.0, 0.0, -1.0}) {
              const SlabDirection out = slabDirection(muDown, 90.0);
              const double tau = depth * thickness;
              const SlabEstimate mc = slab.source(SlabPoint{0.0, 0.0, tau}, out, pointPaths);
              // nu: the cosine between the sun's light and the scattered light, both as propagation directions.
              const double nu = out.x * std::sqrt(1.0 - mu0 * mu0) + out.z * mu0;
              double octaves = 0.0;
              for (int o = 1; o < 3; ++o) {
                const double e = shared::cloudOctavePower(ms.c, o);
                octaves +=
                    shared::cloudOctaveWeight(ms.b, o) * weightScale *
                    shared::cloudPhase(lighting.gForward * e, lighting.gBack * e, lighting.backWeight, lighting.alpha,
                                       nu) *
                    shared::cloudOctaveTransmittance(shared::cloudOctaveExtinctionScale(ms.a, o), tau / mu0, true);
              }
              const double floor = ms.d * shared::cloudFloorSunFactor(mu0) *
                                   shared::cloudEddingtonSlabSource(mu0, tau, thickness, g, muDown);
              std::printf("  z %.1fH %s %.2f|%.2f|%.2f(%.2f)", depth,
                          muDown > 0.5    ? "down"
                          : muDown < -0.5 ? "up  "
                                          : "side",
                          octaves / mc.mean, floor / mc.mean, std::max(octaves, floor) / mc.mean,
                          mc.standardError / mc.mean);
            }
          std::printf("\n");
        }
    }
  }
  return 0;
}
