#include "core/tonemap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/matrix.hpp>

#include "core/color.h"
#include "core/error.h"
#include "core/log.h"
#include "core/png_io.h"
#include "core/scene.h"
#include "core/spectrum.h"

namespace firmament {

namespace {

bool finiteRgb(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// ISO sensitivity and reflected-light meter calibration constant of the EV100 definition.
constexpr double kIso = 100.0;
constexpr double kMeterCalibration = 12.5;

std::string formatNumber(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.6g", v);
  return buffer;
}

}  // namespace

const std::vector<std::string>& toneMapNames() {
  static const std::vector<std::string> names = {"aces", "reinhard", "clamp"};
  return names;
}

ToneMap parseToneMap(std::string_view name) {
  if (name == "aces") return ToneMap::Aces;
  if (name == "reinhard") return ToneMap::Reinhard;
  if (name == "clamp") return ToneMap::Clamp;
  std::string allowed;
  for (const auto& n : toneMapNames()) allowed += (allowed.empty() ? "" : ", ") + n;
  throw InputError("unknown tone map '" + std::string(name) + "'; allowed: " + allowed);
}

const char* toneMapName(ToneMap toneMap) {
  switch (toneMap) {
    case ToneMap::Aces:
      return "aces";
    case ToneMap::Reinhard:
      return "reinhard";
    case ToneMap::Clamp:
      return "clamp";
  }
  return "?";
}

double logAverageLuminance(const Image& image, size_t* nonFinitePixels) {
  double sumLog = 0.0;
  size_t used = 0, skipped = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = image.pixels.data() + i * size_t(image.channels);
    if (!finiteRgb(p)) {
      ++skipped;
      continue;
    }
    sumLog += std::log(std::max(luminanceRec709(p), kAutoExposureMinLuminance));
    ++used;
  }
  if (nonFinitePixels) *nonFinitePixels = skipped;
  return used > 0 ? std::exp(sumLog / double(used)) : kAutoExposureMinLuminance;
}

double autoEv100(const Image& image, size_t* nonFinitePixels) {
  return std::log2(logAverageLuminance(image, nonFinitePixels) * kIso / kMeterCalibration);
}

double autoEv100ForLuminance(double luminance, const ExposureSettings& settings) {
  double ev100 = std::log2(luminance * kIso / kMeterCalibration);
  if (luminance < kNightAdaptationLuminance) {
    const double knee = std::log2(kNightAdaptationLuminance * kIso / kMeterCalibration);
    ev100 = knee + settings.nightAdaptation * (ev100 - knee);
  }
  return std::clamp(ev100, settings.ev100Min, settings.ev100Max);
}

double rodSensitivity(double luminance) { return 0.04 / (0.04 + std::max(luminance, 0.0)); }

double eyeAdaptationTimeConstant(double luminance) {
  const double sigma = rodSensitivity(luminance);
  return sigma * 0.4 + (1.0 - sigma) * 0.1;
}

double ExposureAdaptation::update(double frameLuminance, double dtSeconds, const ExposureSettings& settings) {
  const double target = std::max(frameLuminance, kAutoExposureMinLuminance);
  if (!started_ || settings.temporal == ExposureSettings::TemporalAdaptation::None) {
    started_ = true;
    adapted_ = target;
    return adapted_;
  }
  const double tau = settings.temporal == ExposureSettings::TemporalAdaptation::Eye
                         ? eyeAdaptationTimeConstant(adapted_)
                         : settings.adaptationTimeSeconds;
  const double keep = tau > 0.0 ? std::exp(-std::max(dtSeconds, 0.0) / tau) : 0.0;
  adapted_ = std::exp(std::log(target) + keep * (std::log(adapted_) - std::log(target)));
  return adapted_;
}

double scotopicLuminance(double x, double y, double z) {
  if (!(x > 0.0)) return 0.0;
  return std::max(y * (1.33 * (1.0 + (y + z) / x) - 1.68), 0.0);
}

void applyMesopicVision(float rgb[3]) {
  const glm::dvec3 linear(std::max(0.0f, rgb[0]), std::max(0.0f, rgb[1]), std::max(0.0f, rgb[2]));
  const glm::dvec3 xyz = glm::inverse(xyzToLinearRec709Matrix()) * linear;
  const double sigma = rodSensitivity(xyz.y);
  if (sigma < 1e-5) return;
  // (x, y) = (0.25, 0.25) at unit luminance: X = x / y = 1, Z = (1 - x - y) / y = 2.
  static const glm::dvec3 blue = xyzToLinearRec709(glm::dvec3(1.0, 1.0, 2.0));
  const double scotopic = scotopicLuminance(xyz.x, xyz.y, xyz.z);
  const glm::dvec3 out = (1.0 - sigma) * linear + sigma * scotopic * blue;
  for (int c = 0; c < 3; ++c) rgb[c] = float(std::max(out[c], 0.0));
}

ExposureSettings exposureFromScene(const Scene& scene) {
  ExposureSettings exposure;
  exposure.mode =
      scene.string("/camera/exposure/mode") == "fixed" ? ExposureSettings::Mode::Fixed : ExposureSettings::Mode::Auto;
  exposure.ev100 = scene.number("/camera/exposure/ev100");
  exposure.compensationEv = scene.number("/camera/exposure/compensation_ev");
  exposure.tonemap = scene.string("/camera/exposure/tonemap");
  exposure.nightAdaptation = scene.number("/camera/exposure/night_adaptation");
  exposure.ev100Min = scene.number("/camera/exposure/ev100_min");
  exposure.ev100Max = scene.number("/camera/exposure/ev100_max");
  if (exposure.ev100Min > exposure.ev100Max)
    throw InputError(scene.source() + ": /camera/exposure/ev100_min " + formatNumber(exposure.ev100Min) +
                     " is above /camera/exposure/ev100_max " + formatNumber(exposure.ev100Max) +
                     "; allowed: ev100_min <= ev100_max");
  exposure.vision = scene.string("/camera/exposure/vision") == "mesopic" ? ExposureSettings::Vision::Mesopic
                                                                         : ExposureSettings::Vision::Photopic;
  const std::string temporal = scene.string("/camera/exposure/temporal_adaptation");
  exposure.temporal = temporal == "none"          ? ExposureSettings::TemporalAdaptation::None
                      : temporal == "exponential" ? ExposureSettings::TemporalAdaptation::Exponential
                                                  : ExposureSettings::TemporalAdaptation::Eye;
  exposure.adaptationTimeSeconds = scene.number("/camera/exposure/adaptation_time_s");
  return exposure;
}

double exposureScale(double ev100) { return 1.0 / (1.2 * std::exp2(ev100)); }

void applyToneMap(ToneMap toneMap, const float exposedRgb[3], float displayRgb[3]) {
  const double r = std::max(0.0f, exposedRgb[0]), g = std::max(0.0f, exposedRgb[1]), b = std::max(0.0f, exposedRgb[2]);
  double out[3] = {r, g, b};
  switch (toneMap) {
    case ToneMap::Aces:
      // Narkowicz 2015: x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14). Its derivative's numerator is
      // 1.408x² + 0.7028x + 0.0042 > 0, so it increases on x ≥ 0; it passes 1 near x ≈ 7.24 and is
      // clipped there.
      for (double& x : out) x = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
      break;
    case ToneMap::Reinhard: {
      // Reinhard et al. 2002, eq. 3, applied to luminance; the colour is scaled by L'/L so hue and
      // saturation are kept. A saturated colour can then exceed 1 in one channel: scaling it back by
      // its largest component (rather than clipping each channel) keeps the hue there too.
      const double luminance = luminanceRec709(r, g, b);
      if (luminance > 0.0) {
        const double ratio = 1.0 / (1.0 + luminance);
        for (double& x : out) x *= ratio;
        const double peak = std::max({out[0], out[1], out[2]});
        if (peak > 1.0)
          for (double& x : out) x /= peak;
      } else {
        out[0] = out[1] = out[2] = 0.0;
      }
      break;
    }
    case ToneMap::Clamp:
      break;
  }
  for (int c = 0; c < 3; ++c) displayRgb[c] = float(std::clamp(out[c], 0.0, 1.0));
}

double srgbEncode(double linear) {
  if (!(linear > 0.0)) return 0.0;  // also maps NaN to 0
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

uint8_t quantize8(double v) {
  if (!(v > 0.0)) return 0;
  if (v >= 1.0) return 255;
  return uint8_t(std::lround(v * 255.0));
}

std::vector<uint8_t> toneMapToSrgb8(const Image& image, const ExposureSettings& settings, double* usedEv100,
                                    const double* adaptedLuminance) {
  const ToneMap toneMap = parseToneMap(settings.tonemap);
  if (!std::isfinite(settings.compensationEv) ||
      (settings.mode == ExposureSettings::Mode::Fixed && !std::isfinite(settings.ev100)))
    throw InputError("exposure: EV100 and compensation must be finite numbers");
  if (!std::isfinite(settings.nightAdaptation) || settings.nightAdaptation < 0.0 || settings.nightAdaptation > 1.0 ||
      !(settings.ev100Min <= settings.ev100Max))
    throw InputError("exposure: night_adaptation must be in [0, 1] and ev100_min <= ev100_max");
  const double baseEv100 =
      settings.mode == ExposureSettings::Mode::Auto
          ? autoEv100ForLuminance(adaptedLuminance ? *adaptedLuminance : logAverageLuminance(image), settings)
          : settings.ev100;
  const bool mesopic = settings.vision == ExposureSettings::Vision::Mesopic;
  const double ev100 = baseEv100 - settings.compensationEv;
  if (usedEv100) *usedEv100 = ev100;
  const float scale = float(exposureScale(ev100));

  const int outChannels = settings.keepAlpha && image.channels == 4 ? 4 : 3;
  std::vector<uint8_t> bytes(image.pixelCount() * size_t(outChannels));
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = image.pixels.data() + i * size_t(image.channels);
    uint8_t* q = bytes.data() + i * size_t(outChannels);
    if (!finiteRgb(p)) {
      q[0] = 255, q[1] = 0, q[2] = 255;
    } else {
      float scene[3] = {p[0], p[1], p[2]};
      if (mesopic) applyMesopicVision(scene);
      const float exposed[3] = {scene[0] * scale, scene[1] * scale, scene[2] * scale};
      float display[3];
      applyToneMap(toneMap, exposed, display);
      for (int c = 0; c < 3; ++c) q[c] = quantize8(srgbEncode(display[c]));
    }
    if (outChannels == 4) q[3] = quantize8(p[3]);  // alpha is linear coverage, not sRGB-encoded
  }
  return bytes;
}

double writePngPreview(const std::filesystem::path& path, const Image& image, const ExposureSettings& settings,
                       const double* adaptedLuminance) {
  double ev100 = 0.0;
  std::vector<uint8_t> bytes = toneMapToSrgb8(image, settings, &ev100, adaptedLuminance);
  size_t nonFinite = 0;
  for (size_t i = 0; i < image.pixelCount(); ++i)
    if (!finiteRgb(image.pixels.data() + i * size_t(image.channels))) ++nonFinite;
  if (nonFinite > 0)
    logWarning(path.string() + ": " + std::to_string(nonFinite) + " pixel(s) with NaN or Inf, drawn magenta");
  std::map<std::string, std::string> text = {
      {"Software", "firmament"},
      {"firmament.ev100", formatNumber(ev100)},
      {"firmament.exposure_mode", settings.mode == ExposureSettings::Mode::Auto ? "auto" : "fixed"},
      {"firmament.compensation_ev", formatNumber(settings.compensationEv)},
      {"firmament.tonemap", toneMapName(parseToneMap(settings.tonemap))},
  };
  if (settings.vision == ExposureSettings::Vision::Mesopic) text["firmament.vision"] = "mesopic";
  const int channels = settings.keepAlpha && image.channels == 4 ? 4 : 3;
  writePng(path, image.width, image.height, channels, bytes.data(), text);
  return ev100;
}

}  // namespace firmament
