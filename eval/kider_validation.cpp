#include "eval/kider_validation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "astro/geodetic.h"
#include "astro/sun.h"
#include "astro/time.h"
#include "atmosphere/atmosphere_spectra.h"
#include "atmosphere/reference_medium.h"
#include "core/color.h"
#include "core/error.h"
#include "core/log.h"
#include "core/solar_spectrum_g173.h"
#include "core/spectrum.h"
#include "eval/kider_capture.h"
#include "eval/kider_hemisphere.h"
#include "sky/scene_view.h"
#include "sky/sky_renderer.h"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;
// The published code's spectra: 40 samples 360 + 11.75 i nm, i.e. [360, 830) evenly.
constexpr int kPublishedSpectrumSamples = 40;

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.9g", v);
  return text;
}

// Bilinear read of an equirectangular image's luminance (camera yaw 0: longitude = azimuth, the
// image centre looking north; rows from +90 to -90 degrees of elevation), periodic in azimuth.
double equirectangularLuminance(const Image& image, double azimuth, double elevation) {
  const int w = image.width, h = image.height;
  double u = (azimuth / (2.0 * kPi) + 0.5) * w - 0.5;
  double v = (0.5 - elevation / kPi) * h - 0.5;
  v = std::clamp(v, 0.0, double(h - 1));
  const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
  const double tx = u - x0, ty = v - y0;
  auto at = [&](int x, int y) {
    x = ((x % w) + w) % w;
    y = std::clamp(y, 0, h - 1);
    return luminanceRec709(image.at(x, y));
  };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

// The reference's medium: the scene's atmosphere at the given wavelengths, with the grass albedo
// per wavelength (the scene format holds one albedo; the shared parameters hold one per channel).
reference::SpectralMedium kiderMedium(const AtmosphereSettings& atmosphere, const std::vector<double>& wavelengths) {
  std::vector<shared::AtmosphereParameters> triples;
  for (size_t first = 0; first < wavelengths.size(); first += 3) {
    glm::dvec3 triple;
    for (size_t c = 0; c < 3; ++c) triple[int(c)] = wavelengths[std::min(first + c, wavelengths.size() - 1)];
    shared::AtmosphereParameters p = atmosphereParametersAt(atmosphere, triple);
    p.ground_albedo = glm::dvec3(grassAlbedo(triple.x), grassAlbedo(triple.y), grassAlbedo(triple.z));
    triples.push_back(p);
  }
  return reference::SpectralMedium::fromParameters(triples, wavelengths);
}

// Spectral radiance in each direction, threaded over directions (stream = sample index), with a
// progress bar.
std::vector<ReferenceRadiance> renderDirections(const ReferenceRenderer& renderer, double cameraRadius,
                                                const std::vector<KiderSample>& samples, const std::string& label) {
  std::vector<ReferenceRadiance> out(samples.size());
  std::atomic<size_t> next{0}, done{0};
  int threads = renderer.quality().threads > 0 ? renderer.quality().threads
                                               : int(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min<int>(threads, int(samples.size())));
  auto work = [&] {
    for (size_t i = next++; i < samples.size(); i = next++) {
      out[i] =
          renderer.radiance(glm::dvec3(0.0, 0.0, cameraRadius),
                            astro::enuDirection(samples[i].zenith, samples[i].azimuth), uint64_t(samples[i].index));
      ++done;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  {
    Progress progress(label, samples.size());
    while (done.load() < samples.size()) {
      progress.set(done.load());
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    progress.set(samples.size());
  }
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace

double grassAlbedo(double wavelengthNm) {
  // Feister & Grewe 1995, grass, 360-800 nm every 10 nm.
  static const double kGrass[45] = {0.018, 0.019, 0.019, 0.020, 0.022, 0.024, 0.027, 0.029, 0.030, 0.031, 0.032, 0.032,
                                    0.032, 0.033, 0.035, 0.040, 0.055, 0.073, 0.084, 0.089, 0.089, 0.079, 0.069, 0.063,
                                    0.061, 0.057, 0.052, 0.051, 0.048, 0.042, 0.039, 0.035, 0.035, 0.043, 0.087, 0.156,
                                    0.234, 0.334, 0.437, 0.513, 0.553, 0.571, 0.579, 0.581, 0.587};
  const double u = (wavelengthNm - 360.0) / 10.0;
  if (u <= 0) return kGrass[0];
  if (u >= 44) return kGrass[44];
  const int i = int(u);
  return kGrass[i] + (kGrass[i + 1] - kGrass[i]) * (u - i);
}

double grassAlbedoLuminanceWeighted() {
  double num = 0.0, den = 0.0;
  for (double l = 360.0; l <= 830.0; l += 1.0) {
    const double y = cie1931ColorMatching(l).y;
    num += y * grassAlbedo(l);
    den += y;
  }
  return num / den;
}

std::optional<KiderValidationSettings::AzimuthRefit> kiderAzimuthRefitFromName(const std::string& name) {
  using Refit = KiderValidationSettings::AzimuthRefit;
  if (name == "published") return Refit::published;
  if (name == "log-rings") return Refit::logRings;
  if (name == "none") return Refit::none;
  return std::nullopt;
}

std::optional<KiderValidationSettings::SolarSpectrum> kiderSolarSpectrumFromName(const std::string& name) {
  using Solar = KiderValidationSettings::SolarSpectrum;
  if (name == "instrument") return Solar::instrument;
  if (name == "band-means") return Solar::bandMeans;
  return std::nullopt;
}

double kiderSolarSpectrumScale(const KiderValidationSettings& settings, double wavelengthNm) {
  if (settings.solarSpectrum == KiderValidationSettings::SolarSpectrum::bandMeans) return 1.0;
  // Both at 1 au: the Earth-Sun distance scales the rendered irradiance and cancels here.
  return astmG173ExtraterrestrialSeenWithResolution(wavelengthNm, settings.instrumentFwhmNm) /
         solarIrradiance(wavelengthNm);
}

std::vector<std::string> kiderAtmosphereOverrides() {
  return {"/location/height_m=0",
          "/atmosphere/mie/angstrom_alpha=0.8",
          "/atmosphere/mie/angstrom_beta=0.04",
          "/atmosphere/mie/phase_g=0.7",
          "/atmosphere/mie/single_scattering_albedo=0.8",
          "/atmosphere/ozone/column_dobson=0",
          "/atmosphere/ground_albedo=" + number(grassAlbedoLuminanceWeighted())};
}

const std::vector<PublishedKiderResult>& publishedKiderResults() {
  static const std::vector<PublishedKiderResult> r = {{"Bruneton 2008 (all orders)", 11.2},
                                                      {"Haber 2005", 14.7},
                                                      {"Nishita 1996", 17.9},
                                                      {"Nishita 1993", 26.4},
                                                      {"Hosek-Wilkie", 41.5},
                                                      {"O'Neal", 50.2},
                                                      {"Preetham", 88.2}};
  return r;
}

KiderValidationResult runKiderValidation(const std::filesystem::path& dataDir, const KiderValidationSettings& settings,
                                         gpu::Context* context) {
  const auto start = std::chrono::steady_clock::now();
  KiderValidationResult result;
  for (int i = 0; i < settings.wavelengthCount; ++i)
    result.wavelengths.push_back(settings.firstWavelengthNm + i * settings.wavelengthStepNm);
  std::vector<double> renderWavelengths;
  for (int i = 0; i < settings.quality.wavelengthCount; ++i)
    renderWavelengths.push_back(settings.firstWavelengthNm + i * settings.wavelengthStepNm);
  // Index of each compared wavelength among the rendered ones (they are the same grid).
  if (settings.quality.wavelengthCount < settings.wavelengthCount)
    throw InputError("validate kider: the reference must render at least the compared wavelengths");
  if (!(settings.instrumentFwhmNm > 0.0 && settings.instrumentFwhmNm <= settings.kMaxInstrumentFwhmNm))
    throw InputError("validate kider: the instrument FWHM must be in (0, " + number(settings.kMaxInstrumentFwhmNm) +
                     "] nm, got " + number(settings.instrumentFwhmNm));
  std::vector<double> solarScale;
  for (double l : result.wavelengths) solarScale.push_back(kiderSolarSpectrumScale(settings, l));

  std::unique_ptr<SkyRenderer> gpuRenderer;
  if (context) {
    gpuRenderer = std::make_unique<SkyRenderer>(*context);
    result.gpuDevice = context->description();
  }
  const auto location =
      astro::GeodeticLocation::fromDegrees(settings.latitudeDeg, settings.longitudeDeg, settings.siteHeightM);
  double sumSquares = 0.0, gpuSumSquares = 0.0;

  for (const auto& folder : findKiderCaptureFolders(dataDir)) {
    KiderCapture capture = readKiderCapture(folder, settings.utcOffsetHours);
    if (settings.replaceSampleZero && !replaceKiderSampleZero(capture))
      logWarning("validate kider: " + capture.name + " lacks sample 0, 1 or 31; sample 0 is not replaced");
    KiderCaptureResult c;
    c.capture = capture.name;
    c.utc = capture.utc;
    const auto sun = astro::sunPosition(astro::makeAstroTime(capture.utc), location);
    c.sunZenithDeg = sun.zenith / kDegree;
    c.sunAzimuthComputedDeg = sun.azimuth / kDegree;
    double sunAzimuth = sun.azimuth;
    c.azimuthRefit = "none";
    if (settings.azimuthRefit != KiderValidationSettings::AzimuthRefit::none) {
      // The published fit mirrors sum_i L(360 + 11.75 i nm) over all 40 samples of [360, 830); the
      // log-ring fit the mean over the compared wavelengths.
      std::vector<RingSample> integrated, logMean;
      for (const auto& s : capture.samples) {
        double sum = 0.0, mean = 0.0;
        for (int i = 0; i < kPublishedSpectrumSamples; ++i)
          sum += s.radianceAt(settings.firstWavelengthNm + i * settings.wavelengthStepNm) * settings.wavelengthStepNm;
        for (double l : result.wavelengths) mean += s.radianceAt(l);
        mean /= double(result.wavelengths.size());
        integrated.push_back({s.azimuth, s.elevationDeg * kDegree, sum});
        logMean.push_back({s.azimuth, s.elevationDeg * kDegree, std::log(std::max(mean, 1e-12))});
      }
      const double halfRange = settings.refitHalfRangeDeg * kDegree, step = settings.refitStepDeg * kDegree;
      std::optional<KiderHemisphere> hemisphere;
      if (settings.azimuthRefit == KiderValidationSettings::AzimuthRefit::published)
        hemisphere = KiderHemisphere::fromSamples(integrated);
      if (hemisphere) {
        sunAzimuth = refitSunAzimuthByPublishedSymmetry(*hemisphere, sun.azimuth, halfRange, step);
        c.azimuthRefit = "published";
      } else {
        if (settings.azimuthRefit == KiderValidationSettings::AzimuthRefit::published)
          logWarning("validate kider: " + capture.name +
                     " is not on the scanner's 81-direction layout; the sun azimuth is re-fitted on log rings");
        sunAzimuth = refitSunAzimuthBySymmetry(logMean, sun.azimuth, halfRange, step);
        c.azimuthRefit = "log rings";
      }
    }
    c.sunAzimuthDeg = sunAzimuth / kDegree;

    std::vector<std::string> overrides = kiderAtmosphereOverrides();
    overrides.push_back("/sun/zenith_deg=" + number(c.sunZenithDeg));
    overrides.push_back("/sun/azimuth_deg=" + number(std::remainder(c.sunAzimuthDeg, 360.0)));
    // The sun's direction is given (re-fitted azimuth); its distance comes from the ephemeris: the
    // tabulated solar spectrum is at 1 au, and on 27 May the Earth is 1.013 au from the sun.
    overrides.push_back("/sun/distance_au=" + number(sun.distance / 1.495978707e11));
    overrides.push_back("/camera/height_above_ground_m=" + number(settings.cameraHeightM));
    overrides.push_back("/camera/projection=\"equirectangular\"");
    overrides.push_back("/camera/yaw_deg=0");
    overrides.push_back("/camera/pitch_deg=0");
    overrides.push_back("/camera/width=" + std::to_string(settings.gpuWidth));
    overrides.push_back("/camera/height=" + std::to_string(settings.gpuHeight));
    const Scene scene = Scene::parse(clearSkyDefaultSceneText(), "validate kider " + capture.name, overrides);
    const SceneView view = makeSceneView(scene);

    const ReferenceRenderer renderer(kiderMedium(view.atmosphere, renderWavelengths), view.sunDirection,
                                     settings.quality);
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<ReferenceRadiance> radiance =
        renderDirections(renderer, view.cameraRadius, capture.samples, "reference " + capture.name);
    c.referenceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    Image gpuImage;
    if (gpuRenderer) gpuImage = gpuRenderer->render(scene).image;

    double noise2 = 0.0, se2 = 0.0, bias = 0.0, y2 = 0.0, dy2 = 0.0, gpuDy2 = 0.0, gpuRefDy2 = 0.0, ref2 = 0.0;
    size_t count = 0;
    for (size_t k = 0; k < capture.samples.size(); ++k) {
      const KiderSample& s = capture.samples[k];
      const std::vector<double> total = radiance[k].total();
      KiderDirectionResult d;
      d.index = s.index;
      d.fileAzimuthDeg = s.fileAzimuthDeg;
      d.azimuthDeg = s.azimuth / kDegree;
      d.zenithDeg = s.zenith / kDegree;
      double dirSe2 = 0.0, dirBias = 0.0;
      for (size_t i = 0; i < result.wavelengths.size(); ++i) {
        d.measured.push_back(s.radianceAt(result.wavelengths[i]));
        d.model.push_back(total[i] * solarScale[i]);
        const double e = d.model.back() - d.measured.back();
        dirSe2 += e * e;
        dirBias += e;
        noise2 += std::pow(radiance[k].multipleScatteringStandardError[i] * solarScale[i], 2);
      }
      se2 += dirSe2;
      bias += dirBias;
      count += result.wavelengths.size();
      d.rmseSpectral = 1e3 * std::sqrt(dirSe2 / double(result.wavelengths.size()));
      d.biasSpectral = 1e3 * dirBias / double(result.wavelengths.size());
      std::vector<double> wl(s.radiance.size());
      for (size_t i = 0; i < wl.size(); ++i) wl[i] = s.firstWavelengthNm + double(i) * s.spacingNm;
      d.measuredLuminance = spectrumToXyz(wl, s.radiance).y;
      d.modelLuminance = radiance[k].luminance();
      d.modelLuminanceStandardError = radiance[k].luminanceStandardError;
      d.gpuLuminance = gpuImage.width ? equirectangularLuminance(gpuImage, s.azimuth, kPi / 2 - s.zenith) : NAN;
      y2 += d.measuredLuminance * d.measuredLuminance;
      ref2 += d.modelLuminance * d.modelLuminance;
      dy2 += (d.modelLuminance - d.measuredLuminance) * (d.modelLuminance - d.measuredLuminance);
      gpuDy2 += (d.gpuLuminance - d.measuredLuminance) * (d.gpuLuminance - d.measuredLuminance);
      gpuRefDy2 += (d.gpuLuminance - d.modelLuminance) * (d.gpuLuminance - d.modelLuminance);
      c.directions.push_back(std::move(d));
    }
    c.rmseSpectral = 1e3 * std::sqrt(se2 / double(std::max<size_t>(count, 1)));
    c.bias = 1e3 * bias / double(std::max<size_t>(count, 1));
    c.referenceNoiseRmse = 1e3 * std::sqrt(noise2 / double(std::max<size_t>(count, 1)));
    c.relRmseLuminance = y2 > 0 ? std::sqrt(dy2 / y2) : NAN;
    c.gpuRelRmseLuminance = gpuImage.width && y2 > 0 ? std::sqrt(gpuDy2 / y2) : NAN;
    c.gpuVsReferenceRelRmse = gpuImage.width && ref2 > 0 ? std::sqrt(gpuRefDy2 / ref2) : NAN;
    sumSquares += c.rmseSpectral * c.rmseSpectral;
    gpuSumSquares += c.gpuRelRmseLuminance * c.gpuRelRmseLuminance;
    char line[200];
    std::snprintf(line, sizeof(line),
                  "%s: sun zenith %.2f, azimuth %.2f (computed %.2f) deg: RMSE %.2f e-3, luminance %.2f %%",
                  c.capture.c_str(), c.sunZenithDeg, c.sunAzimuthDeg, c.sunAzimuthComputedDeg, c.rmseSpectral,
                  100 * c.relRmseLuminance);
    logInfo(line);
    result.captures.push_back(std::move(c));
  }
  const double n = double(std::max<size_t>(result.captures.size(), 1));
  result.totalRmseSpectral = std::sqrt(sumSquares / n);
  result.totalGpuRelRmseLuminance = context ? std::sqrt(gpuSumSquares / n) : NAN;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace firmament
