#pragma once
// The clear-sky CPU reference (docs/reference.md): spectral radiance in double precision along
// view rays, orders 0 and 1 by adaptive quadrature, orders >= 2 by a spectral Monte Carlo path
// tracer, converted to CIE XYZ and to linear Rec.709 in cd/m² (the GPU image's units). It shares
// the medium with the GPU code (common/atmosphere_medium.glsl), the ray geometry
// (common/atmosphere_lut.glsl) and the camera model (common/camera.glsl), and none of its
// approximations (no lookup tables, no three-wavelength colour, no multiple-scattering LUT).
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/atmosphere_settings.h"
#include "atmosphere/reference_medium.h"
#include "common/camera.glsl"
#include "core/image.h"

namespace firmament {

struct ReferenceQuality {
  int samplesPerPixel = 256;  // Monte Carlo paths per view ray for orders >= 2 (0: orders 0-1 only)
  int wavelengthCount = 48;   // evenly spaced over 360-830 nm (48: every 10 nm)
  uint64_t seed = 1;
  double quadratureTolerance = 1e-7;  // relative, orders 0 and 1 (per panel, so also of the whole integral)
  double pathTolerance = 1e-6;        // relative, every optical depth inside the path tracer
  int maxBounces = 1000;              // events per path (hard cap)
  int rouletteStartBounce = 100;      // Russian roulette only from this event on
  int forcedSegments = 3;             // path segments sampled conditioned on a collision (view ray = 1)
  int threads = 0;                    // 0: std::thread::hardware_concurrency()
  // The terms, all on for a reference; tests switch them off one by one.
  bool sunDisc = true;
  bool singleScattering = true;
  bool multipleScattering = true;
};

// Spectral radiance along one view ray, W m^-2 sr^-1 nm^-1 at each of the renderer's wavelengths.
struct ReferenceRadiance {
  std::vector<double> sunDisc;                          // order 0: the transmitted, limb-darkened disc
  std::vector<double> singleScattering;                 // order 1: sunlight scattered once by the air or the ground
  std::vector<double> multipleScattering;               // orders >= 2: Monte Carlo mean
  std::vector<double> multipleScatteringStandardError;  // standard error of that mean
  int samples = 0;
  // Photometric results of the total (683 lm/W, CIE 1931 2°): XYZ (Y = luminance, cd/m²) and linear
  // Rec.709 (cd/m² scale), and the Monte Carlo standard error of the luminance.
  glm::dvec3 xyz{0.0};
  glm::dvec3 rgb{0.0};
  double luminanceStandardError = 0.0;

  std::vector<double> total() const;
  double luminance() const { return xyz.y; }
};

class ReferenceRenderer {
 public:
  // sunDirection: unit vector in the planet-centred frame whose axes are the camera's ground point
  // East-North-Up (the camera is on +z).
  ReferenceRenderer(const AtmosphereSettings& settings, glm::dvec3 sunDirection, const ReferenceQuality& quality);
  // A medium built directly (tests: media the scene format cannot express).
  ReferenceRenderer(reference::SpectralMedium medium, glm::dvec3 sunDirection, const ReferenceQuality& quality);
  ~ReferenceRenderer();
  ReferenceRenderer(const ReferenceRenderer&) = delete;
  ReferenceRenderer& operator=(const ReferenceRenderer&) = delete;

  const reference::SpectralMedium& medium() const;
  const std::vector<double>& wavelengths() const;
  const ReferenceQuality& quality() const { return quality_; }
  glm::dvec3 sunDirection() const { return sun_; }

  // Radiance arriving at `camera` (planet-centred, m) from the direction `direction` points to
  // (unit). `stream` selects the random sequence (the pixel index): the result depends on
  // (seed, stream, inputs) only.
  ReferenceRadiance radiance(glm::dvec3 camera, glm::dvec3 direction, uint64_t stream) const;

  // XYZ (683 lm/W) of a spectral radiance sampled at wavelengths(): the CIE integral of its linear
  // interpolation (core/spectrum.h, spectrumToXyz). Linear, so it is a fixed 3 x N matrix.
  glm::dvec3 toXyz(const std::vector<double>& spectralRadiance) const;

 private:
  struct Engine;
  ReferenceQuality quality_;
  glm::dvec3 sun_;
  std::unique_ptr<Engine> engine_;
};

// --- A camera image -----------------------------------------------------------------------------

struct ReferenceImage {
  Image image;  // linear Rec.709, cd/m², RGBA (A = 1), row 0 at the top
  // Per pixel: luminance (cd/m²) and the Monte Carlo standard error of it.
  std::vector<double> luminance;
  std::vector<double> luminanceStandardError;
  // Over the pixels with luminance > 0: median, 95th percentile and maximum of the relative
  // standard error SE(Y)/Y, and the RMS of it.
  double medianRelativeError = 0.0;
  double p95RelativeError = 0.0;
  double maxRelativeError = 0.0;
  double rmsRelativeError = 0.0;
  double seconds = 0.0;  // wall clock
  int threads = 1;
  long long paths = 0, events = 0, rouletteKills = 0, cappedPaths = 0;
  int longestPath = 0;
};

// Renders every pixel of `camera` (the shared cameraRayDirection through pixel centres, as the GPU
// does) from a camera on +z at cameraRadius (m). Pixels run on quality().threads std::threads with
// the pixel index as the random stream: the image does not depend on the thread count.
// progress(done, total) is called from the calling thread about ten times a second.
ReferenceImage renderReferenceImage(const ReferenceRenderer& renderer, double cameraRadius,
                                    const shared::CameraParameters& camera,
                                    const std::function<void(size_t done, size_t total)>& progress = {});

// --- A list of directions (for comparisons with measured skies) ----------------------------------

struct ViewDirection {
  double zenith = 0.0;   // rad
  double azimuth = 0.0;  // rad, clockwise from north (east = pi/2)
};

// Spectral radiance for each direction seen from a camera on +z at cameraRadius; direction k uses
// random stream k. Multithreaded like renderReferenceImage.
std::vector<ReferenceRadiance> renderReferenceDirections(const ReferenceRenderer& renderer, double cameraRadius,
                                                         const std::vector<ViewDirection>& directions);

}  // namespace firmament
