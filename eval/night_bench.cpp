#include "eval/night_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numbers>

#include "astro/moon_photometry.h"
#include "astro/night_sky.h"
#include "astro/star_catalogue.h"
#include "astro/sun.h"
#include "atmosphere/reference_optical_depth.h"
#include "atmosphere/reference_renderer.h"
#include "core/color.h"
#include "core/error.h"
#include "core/log.h"
#include "core/spectrum.h"
#include "sky/night_pass.h"
#include "sky/sky_renderer.h"

namespace firmament {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;
// The scenes' place (scenes/night-*.json, tests/sky/test_night_light.cpp).
constexpr double kLatitude = 46.55, kLongitude = 7.98, kHeight = 1200.0;
constexpr const char* kFullMoon = "2026-01-03T03:00:00Z";  // 1.4 d after full, 41.9 deg high; sun -42 deg
constexpr const char* kNewMoon = "2026-01-18T22:00:00Z";   // Moon below the horizon; sun -57 deg
constexpr const char* kDayMoon = "2026-06-22T15:00:00Z";   // sun 42.3 deg, a 0.6-lit Moon 23.3 deg high

astro::GeodeticLocation place() { return astro::GeodeticLocation::fromDegrees(kLatitude, kLongitude, kHeight); }

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Scene sceneAt(const std::string& utc, const std::string& camera, const std::vector<std::string>& overrides = {}) {
  char json[800];
  std::snprintf(json, sizeof(json),
                R"({"location": {"latitude_deg": %.2f, "longitude_deg": %.2f, "height_m": %.0f},
                    "time": {"utc": "%s"}, "camera": {"height_above_ground_m": 0, %s}})",
                kLatitude, kLongitude, kHeight, utc.c_str(), camera.c_str());
  return Scene::parse(json, "<bench night>", overrides);
}

std::string aimedCamera(double azimuthRad, double elevationRad, double fovDeg, int width, int height,
                        const char* projection = "perspective") {
  char text[300];
  std::snprintf(text, sizeof(text),
                R"("yaw_deg": %.6f, "pitch_deg": %.6f, "fov_deg": %.3f, "width": %d, "height": %d, "projection": "%s")",
                azimuthRad / kDegree, elevationRad / kDegree, fovDeg, width, height, projection);
  return text;
}

// The illuminance a term adds (sky/night_pass.h).
double addedIlluminance(const RenderResult& with, const RenderResult& without) {
  return firmament::addedIlluminance(with.view.camera, with.image.pixels.data(), without.image.pixels.data());
}

// The GPU time of the passes whose label starts with one of `prefixes`, median over repeats, rendering
// `scene` at the timing size.
double passMilliseconds(SkyRenderer& renderer, const std::string& utc, const std::string& camera,
                        const SkyRenderOptions& options, const NightBenchConfig& config,
                        const std::vector<std::string>& prefixes) {
  const Scene scene = sceneAt(
      utc, camera,
      {"/camera/width=" + std::to_string(config.timingWidth), "/camera/height=" + std::to_string(config.timingHeight)});
  std::vector<double> ms;
  for (int k = 0; k < config.repeats; ++k) {
    const RenderResult r = renderer.render(scene, options);
    double sum = 0.0;
    for (const gpu::PassTiming& t : r.timings)
      for (const std::string& p : prefixes)
        if (t.label.rfind(p, 0) == 0) sum += t.milliseconds;
    ms.push_back(sum);
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

// The clear-sky reference's spectral transmittance from a camera at radius r toward cos z = mu (5-nm steps).
struct ReferenceTransmittance {
  std::vector<double> wavelengths;
  reference::SpectralMedium medium;
  reference::ColumnIntegrator integrator;
  ReferenceTransmittance()
      : wavelengths(stepWavelengths()),
        medium(reference::SpectralMedium::fromSettings(AtmosphereSettings{}, wavelengths)),
        integrator(medium, 1e-7) {}
  static std::vector<double> stepWavelengths() {
    std::vector<double> w;
    for (double l = kSpectrumMinNm; l <= kSpectrumMaxNm + 1e-9; l += 5.0) w.push_back(l);
    return w;
  }
  std::vector<double> operator()(double r, double mu) const {
    bool ground = false;
    const reference::RaySegment up = reference::segmentToBoundary(medium, r, mu, &ground);
    std::vector<double> t(wavelengths.size(), 0.0);
    if (ground) return t;
    const reference::ConstituentDensities column = integrator.column(up);
    for (size_t i = 0; i < wavelengths.size(); ++i)
      t[i] = std::exp(-glm::dot(medium.extinctionPerDensity(int(i)), column));
    return t;
  }
  // Luminance of spectrum(lambda) x T(lambda) (spectrum per nm at the 5-nm steps).
  double luminance(const std::function<double(double)>& spectrum, const std::vector<double>& t) const {
    TabulatedSpectrum s;
    s.firstWavelength = wavelengths.front();
    s.spacing = 5.0;
    for (size_t i = 0; i < wavelengths.size(); ++i) s.values.push_back(spectrum(wavelengths[i]) * t[i]);
    return spectrumToXyz(s).y;
  }
};

NightBenchRow row(const std::string& term, const std::string& quantity, const std::string& unit, double frame,
                  double reference) {
  NightBenchRow r;
  r.term = term;
  r.quantity = quantity;
  r.unit = unit;
  r.frame = frame;
  r.reference = reference;
  r.relError = reference != 0.0 ? frame / reference - 1.0 : 0.0;
  r.meanBias = r.relError;
  return r;
}

SkyRenderOptions only(bool moonSky, bool moonDisc, bool skyGlow, bool stars) {
  SkyRenderOptions o;
  o.night.moonSky = moonSky;
  o.night.moonDisc = moonDisc;
  o.night.skyGlow = skyGlow;
  o.night.stars = stars;
  return o;
}

// The Moon's disc at night or in daytime: a 2-deg view at 64 pixels, the disc's sum against
// E_moon(lambda) x T_ref(lambda).
NightBenchRow moonDiscRow(SkyRenderer& renderer, const NightBenchConfig& config, const ReferenceTransmittance& ref,
                          const char* utc, bool day) {
  const astro::MoonLight moon = astro::moonLight(astro::makeAstroTime(utc), place());
  const std::string camera = aimedCamera(moon.azimuth + 0.002, kPi / 2 - moon.zenith - 0.001, 2.0, 64, 64);
  const Scene scene = sceneAt(utc, camera);
  const SkyRenderOptions with = only(false, true, false, false), without = only(false, false, false, false);
  const RenderResult a = renderer.render(scene, with), b = renderer.render(scene, without);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> t = ref(a.view.cameraRadius, std::cos(moon.zenith));
  const double expected = ref.luminance(
      [&](double l) {
        return solarIrradianceTopOfAtmosphere()(l) * astro::moonToSolarIrradianceRatio(moon.illuminanceLux, l);
      },
      t);
  NightBenchRow r = row(day ? "moon_disc_day" : "moon_disc", day ? "disc sum, sun 42 deg" : "disc sum, sun -42 deg",
                        "lx", addedIlluminance(a, b), expected);
  r.referenceSeconds = seconds(start);
  r.passes = day ? "night/moon_disc_day" : "night/night_sky (disc only)";
  // Timed with the Moon at the view's centre and 20 deg across it (the disc ~17 pixels across at 640).
  r.passMs = passMilliseconds(renderer, utc, aimedCamera(moon.azimuth, kPi / 2 - moon.zenith, 20.0, 64, 36), with,
                              config, {day ? "night/moon_disc_day" : "night/night_sky"});
  char note[200];
  std::snprintf(note, sizeof(note), "Moon %.1f deg high, %.0f %% lit, %.4f lx above the air; %d wavelengths",
                90.0 - moon.zenith / kDegree, 100.0 * moon.illuminatedFraction, moon.illuminanceLux, a.spectralSamples);
  r.note = note;
  return r;
}

// The stars over a 180-deg fisheye looking up, and the brightest star above 30 deg alone (2-deg view).
std::vector<NightBenchRow> starRows(SkyRenderer& renderer, const NightBenchConfig& config,
                                    const ReferenceTransmittance& ref) {
  std::vector<NightBenchRow> rows;
  const astro::StarCatalogue* catalogue = nightStarCatalogue();
  if (!catalogue) {
    logWarning("bench night: no star catalogue (Debian package xplanet): the star rows are left out");
    return rows;
  }
  const std::vector<astro::ApparentStar> stars =
      astro::apparentStars(*catalogue, astro::makeAstroTime(kNewMoon), place());
  const SkyRenderOptions with = only(false, false, false, true), without = only(false, false, false, false);
  const int size = config.quick ? 64 : 128;
  const Scene fisheye = sceneAt(kNewMoon, aimedCamera(0.0, kPi / 2, 180.0, size, size, "fisheye"));
  const RenderResult a = renderer.render(fisheye, with), b = renderer.render(fisheye, without);
  // The reference: each star's illuminance times the luminance transmittance of a solar-like spectrum
  // (the stars are drawn white; the frame extincts them with the sun table's channels), tabulated in cos z.
  const auto start = std::chrono::steady_clock::now();
  const int steps = 90;
  std::vector<double> effective(steps + 1, 0.0);
  const auto sun = [](double l) { return solarIrradianceTopOfAtmosphere()(l); };
  const double top = ref.luminance(sun, std::vector<double>(ref.wavelengths.size(), 1.0));
  for (int k = 0; k <= steps; ++k)
    effective[k] = ref.luminance(sun, ref(a.view.cameraRadius, std::max(double(k) / steps, 1e-4))) / top;
  auto transmitted = [&](const astro::ApparentStar& s) {
    const double mu = s.directionEnu.z;
    if (mu <= 0.0) return 0.0;
    const double f = mu * steps;
    const int k = std::min(int(f), steps - 1);
    return s.illuminanceLux * (effective[k] + (f - k) * (effective[k + 1] - effective[k]));
  };
  double expected = 0.0;
  const astro::ApparentStar* brightest = nullptr;
  for (const astro::ApparentStar& s : stars) {
    expected += transmitted(s);
    if (s.zenith < 60.0 * kDegree && (!brightest || s.illuminanceLux > brightest->illuminanceLux)) brightest = &s;
  }
  NightBenchRow all = row("stars", "all stars' sum, 180-deg fisheye", "lx", addedIlluminance(a, b), expected);
  all.referenceSeconds = seconds(start);
  all.passes = "night/night_sky (stars only)";
  all.passMs = passMilliseconds(renderer, kNewMoon, aimedCamera(kPi, 40.0 * kDegree, 60.0, 64, 36), with, config,
                                {"night/night_sky"});
  char note[200];
  std::snprintf(note, sizeof(note), "%zu stars in the catalogue, new-Moon night; the splat and places on the CPU",
                stars.size());
  all.note = note;
  rows.push_back(all);
  if (brightest) {
    const Scene one =
        sceneAt(kNewMoon, aimedCamera(brightest->azimuth + 0.003, kPi / 2 - brightest->zenith - 0.002, 2.0, 64, 64));
    const RenderResult c = renderer.render(one, with), d = renderer.render(one, without);
    NightBenchRow r =
        row("stars", "brightest star above 30 deg", "lx", addedIlluminance(c, d), transmitted(*brightest));
    std::snprintf(note, sizeof(note), "%s, %.1f deg high, %.3g lx above the air",
                  catalogue->stars[size_t(brightest->catalogueIndex)].name.c_str(), 90.0 - brightest->zenith / kDegree,
                  brightest->illuminanceLux);
    r.note = note;
    r.passes = all.passes;
    r.passMs = all.passMs;
    rows.push_back(r);
  }
  return rows;
}

// The sky's own light at zenith angles 0 and 80 deg: a 2-deg view's mean, against the van Rhijn law through
// the air (the spectral light above the air times T_ref) plus what the air scatters of it (the pass's
// isotropic-field estimate, spectrally: (1 - T_ref(lambda)) times the hemisphere's mean above the air).
std::vector<NightBenchRow> skyGlowRows(SkyRenderer& renderer, const NightBenchConfig& config,
                                       const ReferenceTransmittance& ref) {
  std::vector<NightBenchRow> rows;
  const SkyRenderOptions with = only(false, false, true, false), without = only(false, false, false, false);
  const astro::NightSkyFrame frame = astro::nightSkyFrame(astro::makeAstroTime(kNewMoon), place());
  const double planet = ref.medium.groundRadius();
  const auto start = std::chrono::steady_clock::now();
  const double observer = planet + kHeight;
  // The hemisphere's mean above the air per wavelength (uniform in cos z: equal solid angles).
  std::vector<double> mean(ref.wavelengths.size(), 0.0);
  const int n = 16;
  for (int i = 0; i < n; ++i) {
    const double cz = (i + 0.5) / n, sz = std::sqrt(1.0 - cz * cz);
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / n;
      const glm::dvec3 dir(sz * std::sin(phi), sz * std::cos(phi), cz);
      for (size_t k = 0; k < ref.wavelengths.size(); ++k)
        mean[k] += astro::nightSkySpectralRadiance(frame, dir, ref.wavelengths[k], 5.0, observer, planet).total() /
                   double(n * n);
    }
  }
  const double setupSeconds = seconds(start);
  double zenithFrame = 0.0, zenithReference = 0.0;
  for (double zenithDeg : {0.0, 80.0}) {
    const double azimuth = kPi;  // south
    const Scene scene = sceneAt(kNewMoon, aimedCamera(azimuth, (90.0 - zenithDeg) * kDegree, 2.0, 8, 8));
    const RenderResult a = renderer.render(scene, with), b = renderer.render(scene, without);
    double frameL = 0.0;
    for (size_t i = 0; i < a.image.pixelCount(); ++i)
      frameL += (luminanceRec709(a.image.pixels.data() + i * 4) - luminanceRec709(b.image.pixels.data() + i * 4)) /
                double(a.image.pixelCount());
    const auto t0 = std::chrono::steady_clock::now();
    const double z = zenithDeg * kDegree;
    const glm::dvec3 dir(std::sin(z) * std::sin(azimuth), std::sin(z) * std::cos(azimuth), std::cos(z));
    const std::vector<double> t = ref(a.view.cameraRadius, std::cos(z));
    std::vector<double> above(ref.wavelengths.size());
    for (size_t k = 0; k < above.size(); ++k)
      above[k] = astro::nightSkySpectralRadiance(frame, dir, ref.wavelengths[k], 5.0, observer, planet).total();
    auto at = [&](const std::vector<double>& v) {
      return [&v, &ref](double l) { return v[size_t(std::lround((l - ref.wavelengths.front()) / 5.0))]; };
    };
    const double direct = ref.luminance(at(above), t);
    std::vector<double> oneMinusT(t.size());
    for (size_t k = 0; k < t.size(); ++k) oneMinusT[k] = 1.0 - t[k];
    const double scattered = ref.luminance(at(mean), oneMinusT);
    char quantity[80], note[200];
    std::snprintf(quantity, sizeof(quantity), "luminance at zenith angle %.0f deg", zenithDeg);
    NightBenchRow r = row("sky_glow", quantity, "cd/m^2", frameL, direct + scattered);
    std::snprintf(note, sizeof(note), "van Rhijn x T_ref %.4g, scattered %.4g; %.2f mag/arcsec^2 (reference %.2f)",
                  direct, scattered, astro::surfaceBrightnessMagnitude(frameL),
                  astro::surfaceBrightnessMagnitude(direct + scattered));
    r.note = note;
    r.referenceSeconds = seconds(t0) + setupSeconds;
    r.passes = "night/night_sky (the sky's own light only)";
    rows.push_back(r);
    if (zenithDeg == 0.0) zenithFrame = frameL, zenithReference = direct + scattered;
    if (zenithDeg == 80.0) {
      NightBenchRow ratio = row("sky_glow", "80 deg over zenith (van Rhijn brightening)", "ratio", frameL / zenithFrame,
                                (direct + scattered) / zenithReference);
      ratio.passes = r.passes;
      rows.push_back(ratio);
    }
  }
  const double ms = passMilliseconds(renderer, kNewMoon, aimedCamera(kPi, 40.0 * kDegree, 60.0, 64, 36), with, config,
                                     {"night/night_sky"});
  for (NightBenchRow& r : rows) r.passMs = ms;
  return rows;
}

// The moonlit sky: a 90-deg view toward the full Moon's azimuth, 20 deg up, the frame's moonlit sky against
// the reference lit from the Moon's direction (orders 1 and >= 2, no disc) times the Moon's spectrum over the
// Sun's, over the pixels above the horizon.
NightBenchRow moonlitSkyRow(SkyRenderer& renderer, const NightBenchConfig& config) {
  const astro::MoonLight moon = astro::moonLight(astro::makeAstroTime(kFullMoon), place());
  const int w = config.quick ? 16 : 32, h = w / 2;
  const std::string camera = aimedCamera(moon.azimuth, 20.0 * kDegree, 90.0, w, h);
  const Scene scene = sceneAt(kFullMoon, camera);
  SkyRenderOptions off;
  off.night.enabled = false;
  const SkyRenderOptions with = only(true, false, false, false);
  const RenderResult a = renderer.render(scene, with), b = renderer.render(scene, off);
  const auto start = std::chrono::steady_clock::now();
  ReferenceQuality quality;
  quality.sunDisc = false;
  quality.samplesPerPixel = config.referenceSpp > 0 ? config.referenceSpp : (config.quick ? 32 : 128);
  quality.wavelengthCount = config.quick ? 24 : 48;
  quality.threads = config.threads;
  const ReferenceRenderer reference(AtmosphereSettings{}, moon.directionEnu, quality);
  std::vector<ViewDirection> directions;
  std::vector<size_t> pixels;
  const shared::CameraParameters& c = a.view.camera;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      bool valid = false;
      const glm::dvec3 d = shared::cameraRayDirection(c, glm::dvec2(x + 0.5, y + 0.5), valid);
      if (!valid || d.z <= 0.01) continue;
      directions.push_back({std::acos(d.z), std::atan2(d.x, d.y)});
      pixels.push_back(size_t(y) * c.width + x);
    }
  const std::vector<ReferenceRadiance> radiance = renderReferenceDirections(reference, a.view.cameraRadius, directions);
  const std::vector<double>& wavelengths = reference.wavelengths();
  double sumSq = 0.0, sumFrame = 0.0, sumRef = 0.0;
  for (size_t i = 0; i < radiance.size(); ++i) {
    std::vector<double> spectral = radiance[i].total();
    for (size_t k = 0; k < spectral.size(); ++k)
      spectral[k] *= astro::moonToSolarIrradianceRatio(moon.illuminanceLux, wavelengths[k]);
    const double refL = reference.toXyz(spectral).y;
    const double frameL =
        luminanceRec709(a.image.pixels.data() + pixels[i] * 4) - luminanceRec709(b.image.pixels.data() + pixels[i] * 4);
    sumSq += (frameL - refL) * (frameL - refL) / (refL * refL);
    sumFrame += frameL;
    sumRef += refL;
  }
  const double n = double(std::max<size_t>(radiance.size(), 1));
  NightBenchRow r =
      row("moonlit_sky", "sky luminance, 90-deg view toward the Moon", "cd/m^2", sumFrame / n, sumRef / n);
  r.relError = std::sqrt(sumSq / n);
  r.meanBias = sumFrame / sumRef - 1.0;
  r.referenceSeconds = seconds(start);
  r.passes = "night/moon_sky_view + night/night_sky (moonlit sky only)";
  r.passMs = passMilliseconds(renderer, kFullMoon, camera, with, config, {"night/moon_sky_view", "night/night_sky"});
  char note[200];
  std::snprintf(note, sizeof(note), "%zu pixels above the horizon; reference %d paths, %d wavelengths; %d in the frame",
                radiance.size(), quality.samplesPerPixel, quality.wavelengthCount, a.spectralSamples);
  r.note = note;
  return r;
}

// The GPU time of the 4D tables' precompute in a render (0 when they were current).
double tablePrecomputeMilliseconds(const RenderResult& r) {
  double ms = 0.0;
  for (const gpu::PassTiming& t : r.timings)
    for (const char* label :
         {"atmosphere/direct_irradiance", "atmosphere/single_scattering", "atmosphere/scattering_density",
          "atmosphere/indirect_irradiance", "atmosphere/multiple_scattering"})
      if (t.label == label) ms += t.milliseconds;
  return ms;
}

// The twilight: the ground's horizontal illuminance from the sky at the configured sun altitudes (-6, -9,
// -12 deg by default; 2026-06-21 evening), the frame's 180-deg fisheye against the reference over the
// hemisphere (midpoints in cos z and azimuth).
std::vector<NightBenchRow> twilightRows(SkyRenderer& renderer, const NightBenchConfig& config) {
  std::vector<NightBenchRow> rows;
  SkyRenderOptions off;
  off.night.enabled = false;
  std::map<std::string, std::unique_ptr<SkyRenderer>> tableRenderers;
  for (double altitude : config.twilightAltitudesDeg) {
    char utc[32] = "";
    bool found = false;
    for (int minute = 16 * 60; minute < 23 * 60 && !found; ++minute) {
      std::snprintf(utc, sizeof(utc), "2026-06-21T%02d:%02d:00Z", minute / 60, minute % 60);
      found = astro::sunPosition(astro::makeAstroTime(utc), place()).elevation() / kDegree <= altitude;
    }
    if (!found) continue;  // checkNightBenchConfig keeps the altitudes within the evening's range
    const int size = config.quick ? 32 : 64;
    const Scene scene = sceneAt(utc, aimedCamera(0.0, kPi / 2, 180.0, size, size, "fisheye"));
    const RenderResult a = renderer.render(scene, off);
    const shared::CameraParameters& c = a.view.camera;
    double frameLux = 0.0;
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        const glm::dvec2 p(x + 0.5, y + 0.5);
        bool valid = false;
        const glm::dvec3 d = shared::cameraRayDirection(c, p, valid);
        if (!valid || d.z <= 0.0) continue;
        frameLux +=
            luminanceRec709(a.image.pixels.data() + (size_t(y) * c.width + x) * 4) * d.z * pixelSolidAngle(c, p);
      }
    const auto start = std::chrono::steady_clock::now();
    ReferenceQuality quality;
    quality.sunDisc = false;
    quality.samplesPerPixel = config.referenceSpp > 0 ? config.referenceSpp : (config.quick ? 16 : 64);
    quality.wavelengthCount = config.quick ? 24 : 48;
    quality.threads = config.threads;
    const ReferenceRenderer reference(AtmosphereSettings{}, a.view.sunDirection, quality);
    const int zenithSteps = config.quick ? 6 : 10, azimuthSteps = config.quick ? 12 : 24;
    std::vector<ViewDirection> directions;
    std::vector<double> weights;
    for (int i = 0; i < zenithSteps; ++i) {
      // Midpoints in mu^2: E = pi * mean of L over mu^2 uniform (d(mu^2) = 2 mu dmu).
      const double mu = std::sqrt((i + 0.5) / zenithSteps);
      for (int j = 0; j < azimuthSteps; ++j) {
        directions.push_back({std::acos(mu), 2.0 * kPi * (j + 0.5) / azimuthSteps});
        weights.push_back(kPi / double(zenithSteps * azimuthSteps));
      }
    }
    const std::vector<ReferenceRadiance> radiance =
        renderReferenceDirections(reference, a.view.cameraRadius, directions);
    // The frame read at the same directions (nearest fisheye pixel) and summed with the same weights: the
    // comparison without the quadrature's own error; the fisheye's full sum goes into the note.
    double referenceLux = 0.0, variance = 0.0, singleLux = 0.0;
    for (size_t i = 0; i < radiance.size(); ++i) {
      referenceLux += radiance[i].luminance() * weights[i];
      singleLux += reference.toXyz(radiance[i].singleScattering).y * weights[i];
      variance += std::pow(radiance[i].luminanceStandardError * weights[i], 2.0);
    }
    auto atDirections = [&](const RenderResult& frame) {
      double sum = 0.0;
      for (size_t i = 0; i < directions.size(); ++i) {
        const double z = directions[i].zenith, az = directions[i].azimuth;
        bool valid = false;
        const glm::dvec2 p = shared::cameraPixelOfDirection(
            c, glm::dvec3(std::sin(z) * std::sin(az), std::sin(z) * std::cos(az), std::cos(z)), valid);
        const int x = std::clamp(int(p.x), 0, c.width - 1), y = std::clamp(int(p.y), 0, c.height - 1);
        sum += luminanceRec709(frame.image.pixels.data() + (size_t(y) * c.width + x) * 4) * weights[i];
      }
      return sum;
    };
    const double frameAtDirections = atDirections(a);
    char quantity[96], note[400];
    std::snprintf(quantity, sizeof(quantity), "ground illuminance from the sky, sun %.0f deg", altitude);
    NightBenchRow r = row("twilight", quantity, "lx", frameAtDirections, referenceLux);
    r.referenceSeconds = seconds(start);
    r.passes = "sky/* (the day's passes; no night pass)";
    r.passMs = passMilliseconds(renderer, utc, aimedCamera(0.0, 20.0 * kDegree, 60.0, 64, 36), off, config, {"sky/"});
    std::snprintf(note, sizeof(note),
                  "%s; reference +- %.2g (1 standard error), single scattering %.3g lx, %d x %d directions, %d paths, "
                  "%d wavelengths; the frame's fisheye sum %.4g lx, %d wavelengths",
                  utc, std::sqrt(variance), singleLux, zenithSteps, azimuthSteps, quality.samplesPerPixel,
                  quality.wavelengthCount, frameLux, a.spectralSamples);
    r.note = note;
    rows.push_back(r);
    // The same sky from the frame's other ways of computing it: which approximation the difference is in.
    std::vector<std::pair<std::string, SkyRenderOptions>> variants;
    SkyRenderOptions fms = off;
    fms.multipleScattering = MultipleScattering::HillaireFms;
    variants.push_back({"f_ms, sky-view table", fms});
    SkyRenderOptions perPixel = fms;
    perPixel.method = SkyMethod::PerPixel;
    variants.push_back({"f_ms, marched per pixel", perPixel});
    SkyRenderOptions three = fms;
    three.luts.spectralSamples = 3;  // as with clouds, and as the frame light's tables below
    variants.push_back({"f_ms, sky-view table, 3 wavelengths", three});
    SkyRenderOptions tables = off;
    tables.multipleScattering = MultipleScattering::BrunetonTables;
    tables.tables.scatteringOrders = 4;
    tables.luts.spectralSamples = 3;
    variants.push_back({"Bruneton's 4D tables, 4 orders, 3 wavelengths", tables});
    // The twilight tables' size (kTwilightTableSettings) at each order count asked for, at the frame's wavelengths.
    for (int orders : config.twilightTableOrders) {
      tables.tables = kTwilightTableSettings;
      tables.tables.scatteringOrders = orders;
      tables.luts.spectralSamples = a.spectralSamples;
      variants.push_back({"the twilight 4D tables, " + std::to_string(orders) + " orders, " +
                              std::to_string(a.spectralSamples) + " wavelengths",
                          tables});
    }
    for (const auto& [name, options] : variants) {
      // The 4D tables are independent of the sun: one renderer per table setting keeps each computed once.
      SkyRenderer& own =
          options.multipleScattering == MultipleScattering::HillaireFms
              ? renderer
              : *tableRenderers.try_emplace(name, std::make_unique<SkyRenderer>(renderer.context())).first->second;
      const RenderResult v = own.render(scene, options);
      std::snprintf(quantity, sizeof(quantity), "the same, %s", name.c_str());
      NightBenchRow variant = row("twilight", quantity, "lx", atDirections(v), referenceLux);
      const double precompute = tablePrecomputeMilliseconds(v);
      variant.passes = precompute > 0.0 ? "the 4D tables' precompute (atmosphere/*)" : "sky/*";
      variant.passMs = precompute;
      std::snprintf(note, sizeof(note), "%s; %d wavelengths", utc, v.spectralSamples);
      variant.note = note;
      rows.push_back(variant);
    }
    // The tables' ground illuminance (sky/frame_light.h, TableGroundIlluminance: direct plus the ground's
    // skylight table; what decision 0228 compares with the Moon's), read in a night frame with clouds: a
    // cloud layer of no coverage, small noise, a tiny image (clouds take three wavelengths).
    {
      SkyRenderOptions withClouds;
      withClouds.cloudNoise.shapeSize = 32;
      withClouds.cloudNoise.detailSize = 16;
      withClouds.night.stars = withClouds.night.skyGlow = withClouds.night.moonDisc = false;
      const Scene clouded = sceneAt(utc, aimedCamera(0.0, kPi / 2, 90.0, 8, 8),
                                    {R"(/clouds={"layers": [{"kind": "cumulus", "bottom_m": 1500, "top_m": 2500,
                                        "coverage": 0.0}], "quality": "low", "seed": 1})"});
      const RenderResult v = renderer.render(clouded, withClouds);
      if (v.night.run) {  // the frame light is chosen in night frames only (sun below +10 deg)
        NightBenchRow table = row("twilight", "the same, the tables' ground illuminance (frame light)", "lx",
                                  v.light.sunGroundLux, referenceLux);
        table.passes = "sky/frame_light (CPU read-back)";
        std::snprintf(note, sizeof(note), "%s; direct plus the ground's skylight table, %d wavelengths", utc,
                      v.spectralSamples);
        table.note = note;
        rows.push_back(table);
      }
    }
  }
  return rows;
}

}  // namespace

void checkNightBenchConfig(const NightBenchConfig& config) {
  for (double a : config.twilightAltitudesDeg)
    if (!(a >= -19.0 && a <= 30.0))
      throw InputError("--sun-altitude " + std::to_string(a) + ": the twilight rows take -19 to +30 deg");
  for (int n : config.twilightTableOrders)
    if (n < 1 || n > 64) throw InputError("--table-orders " + std::to_string(n) + ": 1 to 64");
  for (const char* t : kNightBenchTerms)
    if (config.term.empty() || config.term == t) return;
  throw InputError("--scenario " + config.term +
                   ": no such night term (moon_disc, stars, sky_glow, moonlit_sky, twilight)");
}

std::vector<NightBenchRow> runNightBench(gpu::Context& context, const NightBenchConfig& config) {
  SkyRenderer renderer(context);
  const ReferenceTransmittance ref;
  std::vector<NightBenchRow> rows;
  auto add = [&](std::vector<NightBenchRow> more) {
    for (NightBenchRow& r : more) {
      char line[300];
      std::snprintf(line, sizeof(line), "%-13s %-45s frame %.5g  reference %.5g  error %+.2f %%  %.2f ms",
                    r.term.c_str(), r.quantity.c_str(), r.frame, r.reference, 100.0 * r.relError, r.passMs);
      logInfo(line);
      rows.push_back(std::move(r));
    }
  };
  auto wanted = [&](const char* term) { return config.term.empty() || config.term == term; };
  if (wanted("moon_disc")) {
    add({moonDiscRow(renderer, config, ref, kFullMoon, false)});
    add({moonDiscRow(renderer, config, ref, kDayMoon, true)});
  }
  if (wanted("stars")) add(starRows(renderer, config, ref));
  if (wanted("sky_glow")) add(skyGlowRows(renderer, config, ref));
  if (wanted("moonlit_sky")) add({moonlitSkyRow(renderer, config)});
  if (wanted("twilight")) add(twilightRows(renderer, config));
  return rows;
}

void writeNightBenchOutputs(const NightBenchConfig& config, const std::vector<NightBenchRow>& rows,
                            const std::string& device) {
  const std::filesystem::path csv = config.outDir / "night_results.csv", md = config.outDir / "night_report.md";
  std::ofstream c(csv), m(md);
  if (!c || !m)
    throw InputError("--out " + config.outDir.string() + ": cannot write night_results.csv/night_report.md");
  c << "term,quantity,unit,frame,reference,rel_error,mean_bias,passes,pass_ms,reference_s,note\n";
  for (const NightBenchRow& r : rows) {
    char line[1000];
    std::snprintf(line, sizeof(line), "%s,\"%s\",%s,%.6g,%.6g,%.5f,%.5f,\"%s\",%.3f,%.3f,\"%s\"\n", r.term.c_str(),
                  r.quantity.c_str(), r.unit.c_str(), r.frame, r.reference, r.relError, r.meanBias, r.passes.c_str(),
                  r.passMs, r.referenceSeconds, r.note.c_str());
    c << line;
  }
  m << "# bench night\n\nDevice: " << device << ". Timing size " << config.timingWidth << "x" << config.timingHeight
    << ", median of " << config.repeats << (config.quick ? " (--quick)" : "") << ".\n";
  if (!config.environmentNote.empty()) m << config.environmentNote << "\n";
  m << "\nError: frame / reference - 1 (moonlit sky: the relative RMSE over the pixels, and the mean's bias). "
       "docs/night.md, \"Error and cost: bench night\", says what each reference is.\n\n";
  m << "| term | quantity | frame | reference | error | mean bias | GPU passes | ms | reference s | note |\n";
  m << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const NightBenchRow& r : rows) {
    char line[1200];
    std::snprintf(line, sizeof(line), "| %s | %s | %.4g %s | %.4g %s | %+.2f %% | %+.2f %% | %s | %.2f | %.2f | %s |\n",
                  r.term.c_str(), r.quantity.c_str(), r.frame, r.unit.c_str(), r.reference, r.unit.c_str(),
                  100.0 * r.relError, 100.0 * r.meanBias, r.passes.c_str(), r.passMs, r.referenceSeconds,
                  r.note.c_str());
    m << line;
  }
}

}  // namespace firmament
