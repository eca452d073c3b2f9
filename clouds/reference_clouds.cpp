#include "clouds/reference_clouds.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "atmosphere/atmosphere_spectra.h"
#include "atmosphere/reference_path_tracer.h"
#include "atmosphere/reference_renderer.h"
#include "common/atmosphere_lut.glsl"
#include "common/cloud_lighting.glsl"
#include "common/cloud_weather.glsl"

namespace firmament {
namespace {

glm::dvec3 directionAround(glm::dvec3 axis, double cosine, double azimuth) {
  const glm::dvec3 helper = std::abs(axis.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
  const glm::dvec3 t = glm::normalize(glm::cross(axis, helper));
  const glm::dvec3 b = glm::cross(axis, t);
  const double sine = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
  return glm::normalize(cosine * axis + sine * (std::cos(azimuth) * t + std::sin(azimuth) * b));
}

}  // namespace

double sampleCloudPhaseCosine(const CloudLightingSettings& lighting, reference::Random& random) {
  if (random.uniform() >= lighting.backWeight)
    return reference::sampleHenyeyGreensteinCosine(lighting.gForward, random.uniform());
  for (;;) {  // accepted on average (1 + alpha (1 + 2 g^2) / 3) / (1 + alpha): ~0.6 for the fit's lobes
    const double nu = reference::sampleHenyeyGreensteinCosine(lighting.gBack, random.uniform());
    if (lighting.alpha <= 0.0 || random.uniform() * (1.0 + lighting.alpha) <= 1.0 + lighting.alpha * nu * nu) return nu;
  }
}

CloudMedium::CloudMedium(std::vector<shared::CloudLayer> layers, NoiseVolume shape, NoiseVolume detail,
                         NoiseVolume curl, CloudWeatherMap weather, double groundRadius_m)
    : layers_(std::move(layers)),
      shape_(std::move(shape)),
      detail_(std::move(detail)),
      curl_(std::move(curl)),
      weather_(std::move(weather)),
      groundRadius_m_(groundRadius_m) {}

double CloudMedium::extinction(size_t i, glm::dvec3 p) const {
  // The same steps as densityAt in shaders/clouds/render_clouds.comp, in double.
  const shared::CloudLayer& layer = layers_[i];
  const double r = glm::length(p);
  if (double h = shared::cloudHeightFraction(layer, r); h <= 0.0 || h >= 1.0) return 0.0;
  const glm::dvec4 weather = weather_.sample(shared::cloudWeatherCoordinate(
      p, groundRadius_m_, glm::dvec2(weather_.width_m, weather_.height_m), weather_.skew, layer.wind_offset));
  bool empty = false;
  const shared::CloudLayer column = shared::cloudColumnLayer(layer, weather, groundRadius_m_, empty);
  if (empty) return 0.0;
  const double ph = shared::cloudHeightFraction(column, r);
  if (ph <= 0.0 || ph >= 1.0) return 0.0;
  const glm::dvec3 local = shared::cloudLocalPosition(column, p);
  const double base =
      shared::cloudShapeDensity(column, ph, shape_.sample(shared::cloudShapeCoordinate(column, local)), weather.x);
  if (base <= 0.0) return 0.0;
  const glm::dvec4 curl = curl_.sample(shared::cloudCurlCoordinate(column, local));
  const glm::dvec4 detail =
      detail_.sample(shared::cloudDetailCoordinate(column, local, glm::dvec2(curl.x, curl.y), ph));
  return column.extinction * shared::cloudDensity(column, ph, base, detail);
}

double CloudMedium::mapCoverage(size_t i, glm::dvec3 p) const {
  const shared::CloudLayer& layer = layers_[i];
  const glm::dvec4 weather = weather_.sample(shared::cloudWeatherCoordinate(
      p, groundRadius_m_, glm::dvec2(weather_.width_m, weather_.height_m), weather_.skew, layer.wind_offset));
  bool empty = false;
  shared::cloudColumnLayer(layer, weather, groundRadius_m_, empty);
  return empty ? 0.0 : shared::cloudSaturate(layer.coverage * weather.x);
}

double CloudMedium::extinction(glm::dvec3 p) const {
  double sum = 0.0;
  for (size_t i = 0; i < layers_.size(); ++i) sum += extinction(i, p);
  return sum;
}

CloudPathTracer::CloudPathTracer(const CloudMedium& medium, const CloudLightingSettings& lighting,
                                 const AtmosphereSettings& atmosphere, glm::dvec3 sun,
                                 const CloudEnvironment& environment, const CloudReferenceSettings& settings)
    : medium_(medium),
      lighting_(lighting),
      exactLighting_(lighting),
      atmosphere_(atmosphereParametersAt(atmosphere, kDefaultWavelengthsNm)),
      sun_(glm::normalize(sun)),
      environment_(environment),
      settings_(settings),
      skyToRgb_(threeWavelengthRadianceToRgb(kDefaultWavelengthsNm, kSkyLambdaPower)),
      sunToRgb_(threeWavelengthRadianceToRgb(kDefaultWavelengthsNm, kSunLambdaPower)) {
  albedo_ = lighting.albedo;
  const double f = settings.maxScatteringOrder == 0 ? cloudPhaseDeltaFraction(lighting, settings.deltaLobeMinG) : 0.0;
  if (f > 0.0) {
    // δ-HG scaling of the first lobe (Joseph, Wiscombe and Weinman 1976): HG(g) ~ g^2 δ + (1 - g^2)
    // HG(g / (1 + g)), which keeps its mean cosine g. The δ part, f = (1 - w) g^2 of all scattering,
    // goes straight on, so it neither attenuates nor turns: sigma_t' = sigma_t (1 - f omega),
    // omega' = omega (1 - f) / (1 - f omega), and the rest of the phase renormalised by 1 - f.
    const double g = lighting.gForward, w = lighting.backWeight;
    deltaFraction_ = f;
    extinctionScale_ = 1.0 - deltaFraction_ * lighting.albedo;
    albedo_ = extinctionScale_ > 0.0 ? lighting.albedo * (1.0 - deltaFraction_) / extinctionScale_ : 0.0;
    lighting_.gForward = g / (1.0 + g);
    lighting_.backWeight = w / (1.0 - deltaFraction_);
    aureoleCosine_ = std::cos(std::min(5.0 * (1.0 - g), shared::kPi));
  }
}

glm::dvec3 CloudPathTracer::sunIrradianceAt(glm::dvec3 p) const {
  const double r = std::max(glm::length(p), atmosphere_.bottom_radius);
  const double muS = std::clamp(glm::dot(p, sun_) / glm::length(p), -1.0, 1.0);
  // The planet's shadow faded over the sun's disc, as transmittanceToSun (Bruneton 2017).
  const double sinH = atmosphere_.bottom_radius / r;
  const double cosH = -std::sqrt(std::max(1.0 - sinH * sinH, 0.0));
  const double a = sinH * atmosphere_.sun_angular_radius;
  const double visible = glm::smoothstep(-a, a, muS - cosH);
  if (visible <= 0.0) return glm::dvec3(0.0);
  const glm::dvec3 depth = shared::opticalDepthToTop(atmosphere_, r, muS, settings_.sunOpticalDepthSteps);
  return visible * glm::exp(-depth) * atmosphere_.solar_irradiance;
}

std::vector<CloudPathTracer::Segment> CloudPathTracer::segments(glm::dvec3 origin, glm::dvec3 direction,
                                                                double tMax) const {
  double r, mu;
  shared::rayRadiusAndCosine(origin, direction, r, mu);
  if (shared::rayIntersectsGround(r, mu, atmosphere_.bottom_radius))
    tMax = std::min(tMax, shared::distanceToBottomAtmosphereBoundary(r, mu, atmosphere_.bottom_radius));
  std::vector<Segment> out;
  for (size_t i = 0; i < medium_.layers().size(); ++i) {
    const shared::CloudLayer& l = medium_.layers()[i];
    glm::dvec2 a, b;
    shared::cloudShellSegments(r, mu, l.bottom_radius, l.top_radius, tMax, a, b);
    if (a.y > a.x) out.push_back({a.x, a.y, i});
    if (b.y > b.x) out.push_back({b.x, b.y, i});
  }
  std::sort(out.begin(), out.end(), [](const Segment& x, const Segment& y) { return x.start < y.start; });
  return out;
}

// Ratio tracking (Novák et al. 2014): T = Π (1 - sigma_t(x_k) / sigma_max) over tentative collisions
// x_k drawn with the majorant; unbiased, and never 0/1 noise like a delta-tracking indicator.
double CloudPathTracer::cloudTransmittance(glm::dvec3 origin, glm::dvec3 direction, reference::Random& random,
                                           double extinctionScale) const {
  double transmittance = 1.0;
  for (const Segment& s : segments(origin, direction, 1e7)) {
    const double majorant = shared::cloudMajorant(medium_.layers()[s.layer]);
    if (!(majorant > 0.0)) continue;
    for (double t = s.start - std::log1p(-random.uniform()) / majorant; t < s.end;
         t -= std::log1p(-random.uniform()) / majorant) {
      transmittance *=
          1.0 - std::min(extinctionScale * medium_.extinction(s.layer, origin + direction * t) / majorant, 1.0);
      if (transmittance < 1e-6) return 0.0;  // negligible; (Russian roulette would keep it unbiased)
    }
  }
  return transmittance;
}

bool CloudPathTracer::trackToCollision(glm::dvec3& x, glm::dvec3 w, double tMax, double extinctionScale,
                                       reference::Random& random) const {
  for (const Segment& s : segments(x, w, tMax)) {
    const double majorant = shared::cloudMajorant(medium_.layers()[s.layer]);
    if (!(majorant > 0.0)) continue;
    for (double t = s.start - std::log1p(-random.uniform()) / majorant; t < s.end;
         t -= std::log1p(-random.uniform()) / majorant) {
      const glm::dvec3 p = x + w * t;
      if (random.uniform() * majorant < extinctionScale * medium_.extinction(s.layer, p)) {
        x = p;
        return true;
      }
    }
  }
  return false;
}

CloudPathTracer::PixelResult CloudPathTracer::pixel(glm::dvec3 origin, glm::dvec3 direction, uint64_t stream) const {
  PixelResult result;
  reference::Random random(settings_.seed, stream);
  const double albedo = albedo_;
  double sumY = 0.0, sumY2 = 0.0, sumT = 0.0, sumOddY = 0.0;
  glm::dvec3 sumRgb(0.0);
  const int n = std::max(settings_.samplesPerPixel, 1);
  for (int sample = 0; sample < n; ++sample) {
    sumT += cloudTransmittance(origin, direction, random, 1.0);  // the true transmittance, as the fast path's alpha
    glm::dvec3 sunlike(0.0), skylike(0.0);
    glm::dvec3 x = origin, w = direction;
    double weight = 1.0;
    bool primary = true;
    int order = 0;  // scattering events of this path so far
    for (int event = 0;; ++event) {
      if (event >= settings_.maxEvents) {
        result.capped++;
        break;
      }
      if (!trackToCollision(x, w, primary ? settings_.maxDistance_m : 1e7, extinctionScale_, random)) {
        // Left the clouds: the background of the view ray is the sky image (composited with T);
        // scattered paths see the environment.
        if (!primary) {
          const double r = glm::length(x), mu = glm::dot(x, w) / r;
          if (shared::rayIntersectsGround(r, mu, atmosphere_.bottom_radius)) {
            sunlike += weight * environment_.groundSun;
            skylike += weight * environment_.groundSky;
          } else {
            skylike += weight * environment_.sky;
          }
        }
        break;
      }
      if (settings_.maxScatteringOrder > 0 && order >= settings_.maxScatteringOrder) break;  // higher orders left out
      ++order;
      result.events++;
      primary = false;
      weight *= albedo;
      // Next event towards the sun (a directional light of irradiance E_sun T_atm).
      const double nuSun = glm::dot(w, sun_);
      const glm::dvec3 sunLight = sunIrradianceAt(x);
      if (sunLight.x + sunLight.y + sunLight.z > 0.0) {
        // TMS (CloudReferenceSettings::exactSingleScattering): at the view ray's first event the scene's
        // phase divided by 1 - f (the scaled medium's scattering coefficient omega' sigma_t' carries 1 - f
        // of omega sigma_t), so the peak's light towards the camera is kept.
        const double phase =
            order == 1 && deltaFraction_ > 0.0 && settings_.exactSingleScattering
                ? shared::cloudPhase(exactLighting_.gForward, exactLighting_.gBack, exactLighting_.backWeight,
                                     exactLighting_.alpha, nuSun) /
                      (1.0 - deltaFraction_)
                : shared::cloudPhase(lighting_.gForward, lighting_.gBack, lighting_.backWeight, lighting_.alpha, nuSun);
        sunlike += weight * phase * cloudTransmittance(x, sun_, random, extinctionScale_) * sunLight;
      }
      // New direction from the two-lobe phase function, sampled exactly (sampleCloudPhaseCosine): the
      // pdf equals the phase function, so the weight is unchanged.
      const double cosine = sampleCloudPhaseCosine(lighting_, random);
      w = directionAround(w, cosine, 2.0 * shared::kPi * random.uniform());
      if (weight < 1e-3) {  // Russian roulette for albedo < 1
        if (random.uniform() > weight * 1e3) break;
        weight = 1e-3;
      }
    }
    const glm::dvec3 rgb = sunToRgb_ * sunlike + skyToRgb_ * skylike;
    const double y = 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
    sumRgb += rgb;
    sumY += y;
    sumY2 += y * y;
    if (sample % 2 == 1) sumOddY += y;
  }
  result.rgb = sumRgb / double(n);
  result.transmittance = sumT / double(n);
  result.luminance = sumY / double(n);
  if (n > 1) {
    result.luminanceStandardError =
        std::sqrt(std::max(0.0, sumY2 / n - result.luminance * result.luminance) / double(n - 1));
    const int odd = n / 2, even = n - odd;
    result.luminanceOddPaths = sumOddY / double(odd);
    result.luminanceEvenPaths = (sumY - sumOddY) / double(even);
  }
  return result;
}

CloudReferenceImage renderCloudReference(const CloudPathTracer& tracer, glm::dvec3 cameraPosition,
                                         const shared::CameraParameters& camera, int threads,
                                         const std::function<void(size_t, size_t)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  CloudReferenceImage out;
  out.image = Image(camera.width, camera.height, 4);
  const size_t count = out.image.pixelCount();
  out.luminance.assign(count, 0.0);
  out.luminanceStandardError.assign(count, 0.0);
  if (tracer.settings().samplesPerPixel >= 2) {
    out.luminanceEvenPaths.assign(count, 0.0);
    out.luminanceOddPaths.assign(count, 0.0);
  }
  out.inAureole.assign(count, 0);
  std::atomic<size_t> next{0}, done{0};
  std::atomic<long long> events{0}, capped{0};
  auto worker = [&] {
    for (size_t i = next++; i < count; i = next++) {
      const int x = int(i % size_t(camera.width)), y = int(i / size_t(camera.width));
      bool valid = true;
      const glm::dvec3 dir = shared::cameraRayDirection(camera, glm::dvec2(x + 0.5, y + 0.5), valid);
      float* p = out.image.at(x, y);
      if (!valid) {
        p[0] = p[1] = p[2] = 0.0f, p[3] = 1.0f;
      } else {
        const CloudPathTracer::PixelResult r = tracer.pixel(cameraPosition, dir, uint64_t(i));
        for (int c = 0; c < 3; ++c) p[c] = float(std::max(r.rgb[c], 0.0));
        p[3] = float(r.transmittance);
        out.luminance[i] = r.luminance;
        out.luminanceStandardError[i] = r.luminanceStandardError;
        if (!out.luminanceOddPaths.empty()) {
          out.luminanceEvenPaths[i] = r.luminanceEvenPaths;
          out.luminanceOddPaths[i] = r.luminanceOddPaths;
        }
        out.inAureole[i] = glm::dot(dir, tracer.sunDirection()) > tracer.aureoleCosine() ? 1 : 0;
        events += r.events;
        capped += r.capped;
      }
      ++done;
    }
  };
  const int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int t = 0; t < n; ++t) pool.emplace_back(worker);
  while (progress && done.load() < count) {
    progress(done.load(), count);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& t : pool) t.join();
  out.paths = (long long)count;
  out.events = events.load();
  out.capped = capped.load();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

CloudReferenceError compareWithCloudReference(const Image& test, const CloudReferenceImage& reference,
                                              double maxTransmittance) {
  if (test.width != reference.image.width || test.height != reference.image.height || test.channels < 3)
    throw std::invalid_argument("compareWithCloudReference: image sizes differ");
  double d2 = 0.0, y2 = 0.0, se2 = 0.0, sumTest = 0.0, sumRef = 0.0;
  // Per cloud pixel: the even paths' luminance (the split), the fast path's and the odd paths' (measured).
  struct Split {
    double by, test, reference;
  };
  std::vector<Split> split;
  const bool halves = reference.luminanceOddPaths.size() == reference.luminance.size() &&
                      reference.luminanceEvenPaths.size() == reference.luminance.size();
  CloudReferenceError e;
  for (size_t i = 0; i < reference.image.pixelCount(); ++i) {
    if (!(reference.image.pixels[4 * i + 3] < maxTransmittance)) continue;
    if (i < reference.inAureole.size() && reference.inAureole[i]) {
      ++e.aureolePixels;
      continue;
    }
    const float* p = test.pixels.data() + size_t(test.channels) * i;
    const double a = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    const double y = reference.luminance[i], se = reference.luminanceStandardError[i];
    d2 += (a - y) * (a - y);
    y2 += y * y;
    se2 += se * se;
    sumTest += a;
    sumRef += y;
    if (halves) split.push_back({reference.luminanceEvenPaths[i], a, reference.luminanceOddPaths[i]});
    ++e.pixels;
  }
  if (e.pixels == 0 || !(y2 > 0.0)) return e;
  e.relRmse = std::sqrt(d2 / y2);
  e.noiseFloor = std::sqrt(se2 / y2);
  e.noiseCorrected = std::sqrt(std::max(d2 - se2, 0.0) / std::max(y2 - se2, 1e-300));
  e.meanTest = sumTest / e.pixels;
  e.meanReference = sumRef / e.pixels;
  e.meanBias = sumRef > 0.0 ? sumTest / sumRef - 1.0 : 0.0;
  // The darkest and brightest quarter by the even paths (ties keep the pixel order), measured
  // against the odd paths.
  if (split.size() >= 4) {
    std::stable_sort(split.begin(), split.end(), [](const Split& l, const Split& r) { return l.by < r.by; });
    const size_t quarter = split.size() / 4;
    auto bias = [](auto begin, auto end) {
      double test = 0.0, ref = 0.0;
      for (auto it = begin; it != end; ++it) {
        test += it->test;
        ref += it->reference;
      }
      return ref > 0.0 ? test / ref - 1.0 : 0.0;
    };
    e.darkQuartileBias = bias(split.begin(), split.begin() + quarter);
    e.brightQuartileBias = bias(split.end() - quarter, split.end());
  }
  return e;
}

CloudEnvironment cloudEnvironmentFromReference(const AtmosphereSettings& atmosphere, glm::dvec3 sun, double r,
                                               int thetaBands, int samplesPerDirection) {
  ReferenceQuality quality;
  quality.samplesPerPixel = samplesPerDirection;
  quality.sunDisc = false;
  quality.threads = 1;
  const std::vector<double> wavelengths{kDefaultWavelengthsNm.x, kDefaultWavelengthsNm.y, kDefaultWavelengthsNm.z};
  const ReferenceRenderer renderer(reference::SpectralMedium::fromSettings(atmosphere, wavelengths), sun, quality);
  // E = ∫ L cos(theta) dOmega over the upper hemisphere, midpoint rule in (theta, phi).
  glm::dvec3 irradiance(0.0);
  const int phiBands = 2 * thetaBands;
  const double dTheta = 0.5 * shared::kPi / thetaBands, dPhi = 2.0 * shared::kPi / phiBands;
  uint64_t stream = 0;
  for (int i = 0; i < thetaBands; ++i)
    for (int j = 0; j < phiBands; ++j) {
      const double theta = (i + 0.5) * dTheta, phi = (j + 0.5) * dPhi;
      const glm::dvec3 dir(std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), std::cos(theta));
      const std::vector<double> l = renderer.radiance(glm::dvec3(0.0, 0.0, r), dir, stream++).total();
      irradiance += glm::dvec3(l[0], l[1], l[2]) * std::cos(theta) * std::sin(theta) * dTheta * dPhi;
    }
  CloudEnvironment env;
  env.sky = irradiance / shared::kPi;
  // The ground below the camera: the sun through the atmosphere and the same sky irradiance (the
  // sky seen from the ground differs a little; part of the stated approximation).
  const shared::AtmosphereParameters p = atmosphereParametersAt(atmosphere, kDefaultWavelengthsNm);
  const double muS = glm::normalize(sun).z;
  const glm::dvec3 groundPoint(0.0, 0.0, p.bottom_radius);
  CloudLightingSettings unused;
  CloudReferenceSettings settings;
  CloudMedium none({}, {}, {}, {}, {}, p.bottom_radius);
  const CloudPathTracer tracer(none, unused, atmosphere, sun, CloudEnvironment{}, settings);
  const glm::dvec3 sunAtGround = tracer.sunIrradianceAt(groundPoint + glm::dvec3(0.0, 0.0, 0.01));
  env.groundSun = p.ground_albedo / shared::kPi * sunAtGround * std::max(muS, 0.0);
  env.groundSky = p.ground_albedo / shared::kPi * irradiance;
  return env;
}

}  // namespace firmament
