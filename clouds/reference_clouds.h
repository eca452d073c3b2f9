#pragma once
// The CPU cloud reference (docs/clouds.md, "Reference"): a volumetric path tracer in double precision
// over the same medium as the GPU march (common/cloud_density.glsl on the read-back noise textures,
// clouds/noise_volume.h), with none of the march's approximations: free paths by delta tracking
// against a majorant per shell (Woodcock et al. 1965), transmittance to the sun by ratio tracking
// (Novák et al. 2014) through every layer, all scattering orders, the same two-lobe phase function
// (dual Henyey-Greenstein or the approximate Mie, common/cloud_lighting.glsl) sampled exactly, albedo
// per event.
// Light: the sun by next-event estimation, through the clouds and through the atmosphere (the shared
// optical depth opticalDepthToTop of common/atmosphere_lut.glsl, evaluated in double at the vertex, no
// table), and an environment for paths that leave the shells: a constant sky radiance over the upper
// hemisphere and a constant ground radiance below (an approximation, stated in docs/clouds.md; the
// air between and around the clouds is not scattered in this reference).
// Radiance is carried at the fast path's three wavelengths (680, 550, 440 nm) in a sun-like and a
// sky-like part and converted with the same Rec.709 matrices, so that a comparison with the GPU
// isolates cloud transport.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "atmosphere/atmosphere_settings.h"
#include "atmosphere/reference_random.h"
#include "clouds/cloud_settings.h"
#include "clouds/cloud_weather_map.h"
#include "clouds/noise_volume.h"
#include "common/camera.glsl"
#include "common/cloud_density.glsl"
#include "core/image.h"

namespace firmament {

// The cosine of a scattering angle drawn from the lighting's two-lobe phase function (cloudPhase) with
// exactly its density: the lobe by its weight, then an HG lobe by inversion; a Draine lobe (alpha > 0)
// by rejection from its HG lobe, accepting with (1 + alpha nu^2) / (1 + alpha), the ratio of the two
// densities up to their normalisation (at most 1).
double sampleCloudPhaseCosine(const CloudLightingSettings& lighting, reference::Random& random);

// The medium: layers, the noise textures and the weather map they read (common/cloud_weather.glsl),
// over a ground sphere of radius groundRadius_m.
class CloudMedium {
 public:
  CloudMedium(std::vector<shared::CloudLayer> layers, NoiseVolume shape, NoiseVolume detail, NoiseVolume curl,
              CloudWeatherMap weather, double groundRadius_m);
  const std::vector<shared::CloudLayer>& layers() const { return layers_; }
  double groundRadius() const { return groundRadius_m_; }
  // Extinction (m^-1) of layer i at p (planet-centred, m); 0 outside its shell.
  double extinction(size_t layer, glm::dvec3 p) const;
  // Extinction (m^-1) of all layers at p: their sum (layers do not overlap, so at most one is non-zero).
  double extinction(glm::dvec3 p) const;
  // The coverage g_c WM_c the weather map asks of layer i in p's column (0 where the column holds none
  // of the layer): the cloud fraction the map means, which the clouds' field is measured against.
  double mapCoverage(size_t layer, glm::dvec3 p) const;

 private:
  std::vector<shared::CloudLayer> layers_;
  NoiseVolume shape_, detail_, curl_;
  CloudWeatherMap weather_;
  double groundRadius_m_;
};

// Light around the clouds, spectral radiance (W m^-2 sr^-1 nm^-1) at the three wavelengths.
struct CloudEnvironment {
  glm::dvec3 sky{0.0};        // above the local horizon (sky-like spectrum)
  glm::dvec3 groundSun{0.0};  // below: the ground's reflection of sunlight (sun-like)
  glm::dvec3 groundSky{0.0};  // below: the ground's reflection of skylight (sky-like)
};

struct CloudReferenceSettings {
  int samplesPerPixel = 64;
  uint64_t seed = 1;
  int maxEvents = 100000;          // scattering events per path (hard cap; counted)
  int sunOpticalDepthSteps = 200;  // trapezoid intervals of the atmosphere's optical depth to the sun
  int threads = 0;                 // 0: all cores
  double maxDistance_m = 80000.0;  // as the fast path: clouds farther along the view ray are not seen
  // Largest number of scattering events per path (0: all orders). 1 gives single scattering only
  // (sunlight by next-event estimation at the first event; light leaving the clouds after it): the part
  // the fast path's first octave approximates with no multiple-scattering model, a diagnostic.
  int maxScatteringOrder = 0;
  // δ-scaling for all orders: a first phase lobe at least this forward (the approximate Mie phase's
  // diffraction peak, HG with g = 0.97 to 0.998 for 5-50 um droplets, ~6000 sr^-1 at 20 um) is split
  // as g^2 δ + (1 - g^2) HG(g / (1 + g)) (δ-HG, Joseph, Wiscombe and Weinman 1976: same mean cosine),
  // and the δ part is folded into the extinction: it scatters straight on. Next-event estimation
  // through the unscaled peak is so heavy-tailed that its mean still climbs with the path count at
  // 16384 paths (docs/clouds.md, "Reference"). Above 1: never. Single-order runs are never scaled.
  double deltaLobeMinG = 0.95;
  // With δ-scaling, the sun's next event at the view ray's first scattering uses the scene's phase
  // p / (1 - f) instead of the truncated one (the TMS correction of Nakajima and Tanaka 1988: the scaled
  // single scattering replaced by one with the exact phase in the scaled medium). The δ sends the
  // peak's light straight on, right for light that is already diffuse but not for the sun seen through
  // a cloud, whose aureole (the peak, ~1.5 deg wide at 20 um) the truncated phase leaves out. It stays
  // quiet: at the first event the scattering angle is the pixel's, not a random one.
  bool exactSingleScattering = true;
};

struct CloudReferenceImage {
  Image image;  // rgb: the clouds' light (cd/m^2, Rec.709), a: their mean transmittance
  std::vector<double> luminance, luminanceStandardError;
  // The luminance of the even- and the odd-numbered paths alone (empty below 2 paths per pixel): two
  // estimates with independent noise, for compareWithCloudReference's split of the pixels by brightness.
  std::vector<double> luminanceEvenPaths, luminanceOddPaths;
  std::vector<uint8_t> inAureole;  // 1: inside CloudPathTracer::aureoleCosine, left out of comparisons
  double seconds = 0.0;
  long long paths = 0, events = 0, capped = 0;
};

class CloudPathTracer {
 public:
  // atmosphere: the scene's atmosphere (evaluated at 680, 550, 440 nm); sun: unit vector in the frame
  // of the camera's ground point (camera on +z).
  CloudPathTracer(const CloudMedium& medium, const CloudLightingSettings& lighting,
                  const AtmosphereSettings& atmosphere, glm::dvec3 sun, const CloudEnvironment& environment,
                  const CloudReferenceSettings& settings);

  // One pixel: the clouds' light (sun-like, sky-like) and transmittance along a view ray, averaged
  // over samplesPerPixel paths with stream `stream`.
  struct PixelResult {
    glm::dvec3 rgb{0.0};  // Rec.709 cd/m^2
    double transmittance = 1.0;
    double luminance = 0.0, luminanceStandardError = 0.0;
    double luminanceEvenPaths = 0.0, luminanceOddPaths = 0.0;  // the two halves' means (2 paths or more)
    long long events = 0, capped = 0;
  };
  PixelResult pixel(glm::dvec3 origin, glm::dvec3 direction, uint64_t stream) const;

  // Spectral sunlight (W m^-2 nm^-1) reaching p through the atmosphere, without clouds.
  glm::dvec3 sunIrradianceAt(glm::dvec3 p) const;

  // The weight f of the phase lobe folded into the extinction (CloudReferenceSettings::deltaLobeMinG), 0
  // without δ-scaling.
  double deltaLobeFraction() const { return deltaFraction_; }
  // With δ-scaling, the cosine of the cone around the sun in which the reference is not trusted: the
  // aureole of a view into the sun through cloud is built by many forward scatterings inside the peak,
  // which the δ sends straight on and TMS restores only to first order. Its half-angle is 5 (1 - g)
  // rad, where a lobe HG(g) has fallen to ~1/200 of its peak (14 deg for g = 0.95, 1.5 deg for the
  // approximate Mie's 20 um droplets; measured for g = 0.95 in tests/clouds/test_cloud_reference.cpp:
  // outside 10 deg +3.5 %, outside 15 deg -2 %, all pixels +34 %). Above 1 (no pixel) without δ-scaling.
  double aureoleCosine() const { return aureoleCosine_; }
  const CloudReferenceSettings& settings() const { return settings_; }
  glm::dvec3 sunDirection() const { return sun_; }

 private:
  struct Segment {
    double start, end;
    size_t layer;
  };
  std::vector<Segment> segments(glm::dvec3 origin, glm::dvec3 direction, double tMax) const;
  // Delta tracking (Woodcock) through the shells in order to the first real collision of a medium
  // whose extinction is extinctionScale times the clouds'; moves x there. False if the ray leaves.
  bool trackToCollision(glm::dvec3& x, glm::dvec3 w, double tMax, double extinctionScale,
                        reference::Random& random) const;
  // Ratio tracking; extinctionScale multiplies the medium's extinction (the δ-scaled transport's, or 1
  // for the view ray's true transmittance, the image's alpha).
  double cloudTransmittance(glm::dvec3 origin, glm::dvec3 direction, reference::Random& random,
                            double extinctionScale) const;

  const CloudMedium& medium_;
  CloudLightingSettings lighting_;       // the transported phase: with δ-scaling, the second lobe alone
  CloudLightingSettings exactLighting_;  // the scene's phase, for the exact first order
  double extinctionScale_ = 1.0;         // 1 - f omega with δ-scaling, else 1
  double albedo_ = 1.0;                  // omega' with δ-scaling, else the lighting's albedo
  double deltaFraction_ = 0.0;
  double aureoleCosine_ = 2.0;
  shared::AtmosphereParameters atmosphere_{};
  glm::dvec3 sun_;
  CloudEnvironment environment_;
  CloudReferenceSettings settings_;
  glm::dmat3 skyToRgb_, sunToRgb_;
};

CloudReferenceImage renderCloudReference(const CloudPathTracer& tracer, glm::dvec3 cameraPosition,
                                         const shared::CameraParameters& camera, int threads,
                                         const std::function<void(size_t, size_t)>& progress = {});

// The luminance error of a fast-path cloud image (rgb: the clouds' light) against the path tracer's,
// over the pixels whose reference transmittance is below maxTransmittance (the cloud pixels) and that
// lie outside the δ-scaled reference's aureole cone (CloudReferenceImage::inAureole; counted). The
// reference carries its own Monte Carlo noise: with Y^ = Y + e, E[e] = 0, E[e^2] = SE^2 and e independent
// of the fast path's error, E[sum (a - Y^)^2] = sum (a - Y)^2 + sum SE^2 and E[sum Y^2] = sum Y^2 +
// sum SE^2, so
//   relRmse          = sqrt(sum (a - Y^)^2 / sum Y^^2)                (what a comparison sees),
//   noiseFloor       = sqrt(sum SE^2 / sum Y^^2)                       (relRmse of a perfect fast path),
//   noiseCorrected   = sqrt(max(sum (a - Y^)^2 - sum SE^2, 0) / (sum Y^^2 - sum SE^2))
// (the same subtraction as docs/bench.md's atmosphere reports), meanBias = mean(a) / mean(Y^) - 1.
// The range: darkQuartileBias / brightQuartileBias are mean(a) / mean(Y) - 1 over the darkest /
// brightest quarter of the cloud pixels. A model that compresses the range is positive in the dark
// quarter and negative in the bright one. The pixels are split by the even-numbered paths' luminance
// and the bias is measured against the odd-numbered paths' (CloudReferenceImage::luminanceEvenPaths,
// luminanceOddPaths), whose noise is independent of the split. A split by the same noisy reference that
// is measured files the pixels whose noise came out high under "bright", so even a perfect fast path
// would show too dark there and too bright in the dark quarter (regression to the mean); a split by the
// fast path's own luminance files its own errors the same way and shows a range expanded. With fewer
// than 2 paths per pixel both are 0.
struct CloudReferenceError {
  double relRmse = 0.0, noiseFloor = 0.0, noiseCorrected = 0.0, meanBias = 0.0;
  double darkQuartileBias = 0.0, brightQuartileBias = 0.0;
  double meanTest = 0.0, meanReference = 0.0;
  int pixels = 0;
  int aureolePixels = 0;  // cloud pixels left out: inside the aureole cone
};
CloudReferenceError compareWithCloudReference(const Image& test, const CloudReferenceImage& reference,
                                              double maxTransmittance = 0.95);

// The environment from the clear-sky CPU reference (atmosphere/reference_renderer.h) at three
// wavelengths: the irradiance E_sky on a horizontal surface at radius r (m), by a midpoint rule over
// thetaBands x 2 thetaBands directions of the upper hemisphere with samplesPerDirection paths each;
// sky = E_sky / pi, and the ground (Lambertian, the atmosphere's albedo) lit by the transmitted sun
// and E_sky at the ground below the camera.
CloudEnvironment cloudEnvironmentFromReference(const AtmosphereSettings& atmosphere, glm::dvec3 sun, double r,
                                               int thetaBands = 6, int samplesPerDirection = 8);

}  // namespace firmament
