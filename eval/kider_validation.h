#pragma once
// `firmament validate kider`: the CPU reference (and, labelled apart, the fast GPU path) against the
// measured skies of Kider et al. 2014, with the conventions and error measure of Bruneton's published
// evaluation of clear-sky models (IEEE TVCG 2017), so the total is comparable with the published
// values (docs/validation.md). Nothing is fitted to the captures except the sun azimuth re-fit that
// the published evaluation does (a correction of the scanner's drift, not of the model).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/reference_renderer.h"
#include "core/scene.h"
#include "gpu/context.h"

namespace firmament {

struct KiderValidationSettings {
  // Site (README): the roof of Rhodes Hall, Cornell; capture names are local time, EDT = UTC - 4.
  double latitudeDeg = 42.443449, longitudeDeg = -76.481962, siteHeightM = 250.0;
  double utcOffsetHours = -4.0;
  // Conventions of the published evaluation.
  bool replaceSampleZero = true;
  // The sun azimuth's re-fit: `published` mirrors the spectrally integrated radiance, interpolated
  // as the published code does, about the candidate plane (kider_hemisphere.h; captures not on the
  // scanner's 81-direction layout fall back to `logRings`); `logRings` compares log radiances on the
  // measured rings only (this project's first method); `none` keeps the computed azimuth.
  enum class AzimuthRefit { published, logRings, none };
  AzimuthRefit azimuthRefit = AzimuthRefit::published;
  double refitHalfRangeDeg = 20.0, refitStepDeg = 0.2;
  // Error measure: 31 wavelengths 360 + 11.75 i nm (360 ... 712.5), i.e. the first 31 of 40 evenly
  // spaced samples of [360, 830) as in the published code.
  double firstWavelengthNm = 360.0, wavelengthStepNm = 11.75;
  int wavelengthCount = 31;
  // The reference renders 41 wavelengths 360 + 11.75 i (to 830 nm, for the luminance), so the 31
  // compared ones are its own samples, not interpolations.
  ReferenceQuality quality = [] {
    ReferenceQuality q;
    q.samplesPerPixel = 4096;
    q.wavelengthCount = 41;
    return q;
  }();
  // The solar spectrum under the compared spectra. `instrument` (the default): ASTM G-173 read through
  // the spectroradiometer's line shape, a Gaussian of `instrumentFwhmNm` (3 nm, ASD's usual VNIR
  // figure; docs/validation.md gives the totals for 2 and 5 nm too), because the measured radiance at λ resolves the
  // Fraunhofer lines that a 10-nm bin averages away (at 395.25 nm, between Ca II H and K, the 3-nm reading is 0.71 of
  // the bin's value). Each wavelength is independent (elastic scattering), so the model's radiance at λ scales with the
  // solar irradiance at λ: the rendered spectra are rescaled by reading / bin value. `bandMeans`: the
  // atmosphere's own 10-nm means, as the published comparison's models used. The luminances always
  // use the 10-nm means (an integral over wavelength, where the bins are the right input).
  enum class SolarSpectrum { instrument, bandMeans };
  SolarSpectrum solarSpectrum = SolarSpectrum::instrument;
  double instrumentFwhmNm = 3.0;
  static constexpr double kMaxInstrumentFwhmNm = 8.0;  // keeps the line shape inside the G-173 table
  double cameraHeightM = 1.0;                          // above the ground sphere
  bool gpu = true;                                     // also sample the fast path's luminance in the same directions
  int gpuWidth = 1440, gpuHeight = 720;                // equirectangular image the fast path renders
};

// The atmosphere of the comparison as scene overrides on the built-in default scene (README:
// Angstrom alpha 0.8, beta 0.04, Cornette-Shanks g 0.7, aerosol single-scattering albedo 0.8, no
// ozone, the ground at sea level, the ground albedo of grass (its luminance-weighted mean for the
// GPU's single value)); the sun's direction and the camera are added per capture.
std::vector<std::string> kiderAtmosphereOverrides();

// Grass spectral albedo, Feister & Grewe 1995 ("Spectral albedo measurements in the UV and visible
// region over different types of surfaces", Photochemistry and Photobiology 62, 736-744), 360-800 nm
// every 10 nm as used by the published evaluation; linear in between, held constant outside.
double grassAlbedo(double wavelengthNm);
// ∫ ȳ(λ) a(λ) dλ / ∫ ȳ(λ) dλ over 360-830 nm: the single albedo the three-wavelength GPU path gets.
double grassAlbedoLuminanceWeighted();

// "instrument" or "band-means"; nullopt for anything else.
std::optional<KiderValidationSettings::SolarSpectrum> kiderSolarSpectrumFromName(const std::string& name);
// The factor the rendered spectral radiance at `wavelengthNm` is scaled by for the comparison:
// the solar irradiance the settings ask for over the one the atmosphere rendered with (1 for bandMeans).
double kiderSolarSpectrumScale(const KiderValidationSettings& settings, double wavelengthNm);

// "published", "log-rings" or "none"; nullopt for anything else.
std::optional<KiderValidationSettings::AzimuthRefit> kiderAzimuthRefitFromName(const std::string& name);

struct KiderDirectionResult {
  int index = 0;
  double fileAzimuthDeg = 0.0, azimuthDeg = 0.0, zenithDeg = 0.0;
  std::vector<double> measured, model;  // at the compared wavelengths, W m^-2 sr^-1 nm^-1
  double measuredLuminance = 0.0, modelLuminance = 0.0, modelLuminanceStandardError = 0.0;  // cd/m²
  double gpuLuminance = 0.0;                                                                // NaN without the GPU path
  double rmseSpectral = 0.0;  // 1e-3 W m^-2 sr^-1 nm^-1, over the compared wavelengths
  double biasSpectral = 0.0;  // mean(model - measured), same unit
};

struct KiderCaptureResult {
  std::string capture, utc;
  double sunZenithDeg = 0.0;           // computed (apparent)
  double sunAzimuthComputedDeg = 0.0;  // computed, clockwise from north
  double sunAzimuthDeg = 0.0;          // used: re-fitted by symmetry (or the computed one)
  std::string azimuthRefit;            // the re-fit that gave it: "published", "log rings" or "none"
  double rmseSpectral = 0.0;           // 1e-3 W m^-2 sr^-1 nm^-1, all directions x wavelengths
  double relRmseLuminance = 0.0;       // sqrt(mean((Ym - Ymeas)²)) / sqrt(mean(Ymeas²)) over the directions
  double bias = 0.0;                   // mean(model - measured) spectral, 1e-3 W m^-2 sr^-1 nm^-1
  double gpuRelRmseLuminance = 0.0;    // the fast path against the measurements (NaN without it)
  double gpuVsReferenceRelRmse = 0.0;  // the fast path against the reference, same directions
  double referenceNoiseRmse = 0.0;     // sqrt(mean(SE²)) of the reference's Monte Carlo noise, same unit
  double referenceSeconds = 0.0;
  std::vector<KiderDirectionResult> directions;
};

struct KiderValidationResult {
  std::vector<double> wavelengths;  // compared, nm
  std::vector<KiderCaptureResult> captures;
  double totalRmseSpectral = 0.0;  // sqrt(mean over captures of rmse²), 1e-3 W m^-2 sr^-1 nm^-1
  double totalGpuRelRmseLuminance = 0.0;
  std::string gpuDevice;  // empty without the GPU path
  double seconds = 0.0;
};

// Validates every capture folder under dataDir (findKiderCaptureFolders). `context` may be null
// (no GPU comparison). Progress bars on stderr.
KiderValidationResult runKiderValidation(const std::filesystem::path& dataDir, const KiderValidationSettings& settings,
                                         gpu::Context* context);

// results.csv (per capture), per_direction.csv, per_wavelength.csv and report.md in outDir.
void writeKiderValidationOutputs(const std::filesystem::path& outDir, const KiderValidationSettings& settings,
                                 const KiderValidationResult& result);

// The published totals on these four captures (README; Bruneton 2017), best first.
struct PublishedKiderResult {
  const char* model;
  double totalRmse;  // 1e-3 W m^-2 sr^-1 nm^-1
};
const std::vector<PublishedKiderResult>& publishedKiderResults();

}  // namespace firmament
