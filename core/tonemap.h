#pragma once
// HDR → display: exposure (EV100, fixed or automatic), a named tone map, then the sRGB transfer
// function, 8 bits per channel (docs/formats.md, "PNG preview").
//
// Exposure follows Lagarde & de Rousiers, "Moving Frostbite to Physically Based Rendering 3.0"
// (SIGGRAPH 2014 course notes, section 5.1): with ISO S = 100, reflected-light meter constant K = 12.5
// and lens/vignetting factor q = 0.65 (so 78/(q·S) = 1.2),
//   EV100 = log2(L_avg · S / K)           (automatic: L_avg the log-average scene luminance, cd/m²)
//   exposure scale = 1 / (1.2 · 2^EV100)  (the luminance that just saturates the sensor is 1.2·2^EV100)
// A compensation of +c EV brightens by 2^c: the effective EV100 is EV100 − c.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"

namespace firmament {

class Scene;

enum class ToneMap {
  Aces,      // Narkowicz 2015, "ACES Filmic Tone Mapping Curve" (fit of the ACES RRT+ODT), per channel
  Reinhard,  // Reinhard et al. 2002, L/(1+L) on luminance; colour scaled by the same ratio (hue kept)
  Clamp,     // no curve: clip to [0, 1]
};

struct ExposureSettings {
  enum class Mode { Auto, Fixed };
  // How the preview treats colour at low light: as a camera does (photopic), or as a person's eye does
  // (mesopic: rods take over below a few cd/m², colour fades to a scotopic blue; applyMesopicVision).
  enum class Vision { Photopic, Mesopic };
  // How the automatic exposure follows a sequence: each frame metered alone, the eye's time constants
  // (eyeAdaptationTimeConstant), or one fixed time constant (adaptationTimeSeconds).
  enum class TemporalAdaptation { None, Eye, Exponential };
  Mode mode = Mode::Auto;
  double ev100 = 15.0;           // used when mode == Fixed (15 ≈ a sunny day, "sunny 16" at ISO 100)
  double compensationEv = 0.0;   // added brightness in stops, in both modes
  std::string tonemap = "aces";  // "aces", "reinhard" or "clamp"
  bool keepAlpha = false;        // write the image's A channel (as is, linear) into the preview
  // Auto mode at night (autoEv100ForLuminance): the fraction of a fall of the log-average luminance below
  // kNightAdaptationLuminance that the exposure makes up for. 1: a night as bright as day; 0: no adaptation.
  double nightAdaptation = 0.8;
  double ev100Min = -10.0;  // auto mode's limits (a camera's metering range), before compensation
  double ev100Max = 24.0;
  Vision vision = Vision::Photopic;
  TemporalAdaptation temporal = TemporalAdaptation::Eye;
  double adaptationTimeSeconds = 1.0;  // for TemporalAdaptation::Exponential
};

// The scene's /camera/exposure section (docs/scene.md) as settings.
ExposureSettings exposureFromScene(const Scene& scene);

// Names accepted by parseToneMap, in the order help texts list them.
const std::vector<std::string>& toneMapNames();
// Unknown names → InputError listing the allowed ones.
ToneMap parseToneMap(std::string_view name);
const char* toneMapName(ToneMap toneMap);

// Luminance below this (cd/m², about a tenth of a moonless night sky's) counts as this in the log
// average, so that black pixels cannot drive the average to zero.
inline constexpr double kAutoExposureMinLuminance = 1e-5;

// Automatic EV100 = log2(L_avg · 100 / 12.5), L_avg = exp(mean(ln(max(Y, kAutoExposureMinLuminance))))
// over the pixels whose R, G, B are all finite. Non-finite pixels are skipped and counted in
// *nonFinitePixels when given. An image with no finite pixel gives the EV100 of the floor luminance.
double autoEv100(const Image& image, size_t* nonFinitePixels = nullptr);

// The log-average luminance autoEv100 meters, exp(mean(ln(max(Y, kAutoExposureMinLuminance)))).
double logAverageLuminance(const Image& image, size_t* nonFinitePixels = nullptr);

// Below this adaptation luminance the automatic exposure stops following the scene one for one: 5 cd/m²,
// the top of the mesopic range (CIE 191:2010, "Recommended system for mesopic photometry", 0.005-5 cd/m²),
// about the sky's luminance when the Sun is 6-7° below the horizon (the end of civil twilight).
inline constexpr double kNightAdaptationLuminance = 5.0;

// The automatic EV100 for an adaptation luminance L (cd/m²), before compensation:
//   L >= 5 cd/m²: log2(L · 100 / 12.5), the meter's value (today's daytime exposure, unchanged);
//   L <  5 cd/m²: log2(5 · 8) + a · log2(L / 5), a = settings.nightAdaptation: the exposure makes up only
//                 the fraction a of the fall below 5 cd/m², so a night stays darker than a day, as a night
//                 looks to a dark-adapted eye (a = 0.8: a moonless night, 2e-4 cd/m², 2.9 stops darker
//                 than day; a full-moon sky, ~7e-3 cd/m², 1.9 stops darker);
// then clamped to [ev100Min, ev100Max]. Continuous and non-decreasing in L.
double autoEv100ForLuminance(double luminance, const ExposureSettings& settings);

// The eye's adaptation time constant at an adaptation luminance L (cd/m²), Krawczyk, Myszkowski & Seidel
// (2005), "Perceptual effects in real-time tone mapping" (SCCG), after Durand & Dorsey (2000):
//   tau(L) = sigma(L) · 0.4 s + (1 - sigma(L)) · 0.1 s,   sigma(L) = 0.04 / (0.04 + L)  (rodSensitivity)
// rods adapt in 0.4 s, cones in 0.1 s; sigma is the share of the rods.
double rodSensitivity(double luminance);
double eyeAdaptationTimeConstant(double luminance);

// Temporal adaptation of the metered luminance over a sequence: the adapted log luminance moves toward each
// frame's log-average by 1 - exp(-dt / tau) (an exponential filter in log luminance: no overshoot, no
// flicker from frame-to-frame noise, no jump at sunset). The first frame starts adapted.
class ExposureAdaptation {
 public:
  // Feeds one frame's log-average luminance, `dtSeconds` after the previous frame; returns the adapted one.
  double update(double frameLuminance, double dtSeconds, const ExposureSettings& settings);
  bool started() const { return started_; }
  double adaptedLuminance() const { return adapted_; }

 private:
  bool started_ = false;
  double adapted_ = 0.0;
};

// Scotopic luminance of CIE XYZ (the Y in cd/m²), Larson, Rushmeier & Piatko (1997) as Jensen et al. (2001)
// use it for the night sky: V = Y (1.33 (1 + (Y + Z) / X) - 1.68), 0 where X <= 0 or V < 0.
double scotopicLuminance(double x, double y, double z);

// Mesopic vision of one linear Rec.709 pixel (cd/m²), in place: the photopic colour blended toward the
// scotopic luminance shown in a desaturated blue of chromaticity (0.25, 0.25) — the blue shift Jensen et al.
// (2001) give night images — by the rods' share sigma(Y) (rodSensitivity): 0.5 at 0.04 cd/m², 0.008 at
// 5 cd/m²; the photopic colour is kept where sigma is negligible (daylight: under 1e-5).
void applyMesopicVision(float rgb[3]);

// 1 / (1.2 · 2^ev100): multiplies scene luminance (cd/m²) into the tone map's input.
double exposureScale(double ev100);

// The curve applied to exposed, linear Rec.709 RGB (negative components are taken as 0).
// Each output component is in [0, 1]; 0 maps to 0; each curve is non-decreasing in exposure.
void applyToneMap(ToneMap toneMap, const float exposedRgb[3], float displayRgb[3]);

// The sRGB transfer function (IEC 61966-2-1:1999): 12.92·c for c ≤ 0.0031308, else 1.055·c^(1/2.4) − 0.055.
double srgbEncode(double linear);
// round(255 · clamp(v, 0, 1)).
uint8_t quantize8(double v);

// The full pipeline: exposure, tone map, sRGB encode, quantize. Returns width·height·channels bytes,
// channels = 4 when settings.keepAlpha and the image has alpha, else 3. A pixel with a non-finite
// R, G or B is drawn magenta (255, 0, 255) so that it is visible. *usedEv100 receives the effective
// EV100 (after compensation): a Fixed run with that value and no compensation gives the same bytes.
// `adaptedLuminance`, when given, replaces the image's own log average in auto mode (a sequence's
// ExposureAdaptation); the vision and night adaptation settings apply as above.
std::vector<uint8_t> toneMapToSrgb8(const Image& image, const ExposureSettings& settings, double* usedEv100 = nullptr,
                                    const double* adaptedLuminance = nullptr);

// Tone maps and writes an 8-bit PNG (atomically) with tEXt entries for the exposure and tone map
// used; warns with the count of non-finite pixels. Returns the effective EV100.
double writePngPreview(const std::filesystem::path& path, const Image& image, const ExposureSettings& settings,
                       const double* adaptedLuminance = nullptr);

}  // namespace firmament
