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

enum class ToneMap {
  Aces,      // Narkowicz 2015, "ACES Filmic Tone Mapping Curve" (fit of the ACES RRT+ODT), per channel
  Reinhard,  // Reinhard et al. 2002, L/(1+L) on luminance; colour scaled by the same ratio (hue kept)
  Clamp,     // no curve: clip to [0, 1]
};

struct ExposureSettings {
  enum class Mode { Auto, Fixed };
  Mode mode = Mode::Auto;
  double ev100 = 15.0;          // used when mode == Fixed (15 ≈ a sunny day, "sunny 16" at ISO 100)
  double compensationEv = 0.0;  // added brightness in stops, in both modes
  std::string tonemap = "aces";  // "aces", "reinhard" or "clamp"
  bool keepAlpha = false;        // write the image's A channel (as is, linear) into the preview
};

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
std::vector<uint8_t> toneMapToSrgb8(const Image& image, const ExposureSettings& settings,
                                    double* usedEv100 = nullptr);

// Tone maps and writes an 8-bit PNG (atomically) with tEXt entries for the exposure and tone map
// used; warns with the count of non-finite pixels. Returns the effective EV100.
double writePngPreview(const std::filesystem::path& path, const Image& image, const ExposureSettings& settings);

}  // namespace firmament
