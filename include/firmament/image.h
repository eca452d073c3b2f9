#pragma once
// A frame's preview: the scene's exposure (/camera/exposure, docs/scene.md: automatic or a fixed EV100,
// compensation, tone map, the eye's adaptation through a sequence) applied to a SkyFrame, written as an
// 8-bit sRGB PNG or returned as pixels for a window. The EXR (saveExr, firmament/sky.h) stays absolute
// cd/m²; the preview is for eyes.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "firmament/sky.h"

namespace firmament {

class Exposure {
 public:
  explicit Exposure(const Sky& sky);  // the sky's current /camera/exposure
  // A scene's (InputError naming `source` when invalid).
  static Exposure fromSceneJson(const std::string& sceneJson, const std::string& source = "<scene json>");
  Exposure(const Exposure& other);
  Exposure& operator=(const Exposure& other);
  ~Exposure();

  bool automatic() const;  // the EV100 from the frame's log-average luminance (else fixed)
  void setAutomatic(bool automatic);
  double ev100() const;  // the fixed EV100
  void setEv100(double ev100);
  double compensation() const;  // stops added in both modes
  void setCompensation(double stops);
  std::string toneMap() const;  // "aces", "reinhard" or "clamp"

  // The EV100 the preview uses for an adapted luminance (cd/m²): automatic or fixed, less compensation.
  double ev100For(double adaptedLuminance) const;
  // 8-bit sRGB RGBA, row 0 at the top; adaptedLuminance (from EyeAdaptation) replaces the frame's own
  // log-average in the automatic exposure. usedEv100: the EV100 applied.
  std::vector<uint8_t> toSrgb8(const SkyFrame& frame, double* usedEv100 = nullptr,
                               const double* adaptedLuminance = nullptr) const;
  // Writes the PNG preview atomically (with tEXt entries for the exposure and tone map); returns the EV100.
  double savePng(const SkyFrame& frame, const std::string& path, const double* adaptedLuminance = nullptr) const;

 private:
  friend class EyeAdaptation;
  struct Settings;
  explicit Exposure(std::unique_ptr<Settings> settings);
  std::unique_ptr<Settings> settings_;
};

// The eye's adaptation through a sequence (/camera/exposure/temporal_adaptation): the luminance the
// automatic exposure follows, moving from frame to frame toward each frame's log-average.
class EyeAdaptation {
 public:
  EyeAdaptation();
  ~EyeAdaptation();
  EyeAdaptation(const EyeAdaptation&) = delete;
  EyeAdaptation& operator=(const EyeAdaptation&) = delete;
  // Takes the next frame's log-average luminance dt_s after the last; returns the adapted luminance.
  double update(double logAverageLuminance, double dt_s, const Exposure& exposure);
  bool started() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The log-average luminance of a frame's pixels (cd/m², the automatic exposure's input), over the finite
// ones; nonFinitePixels counts the others.
double logAverageLuminance(const SkyFrame& frame, size_t* nonFinitePixels = nullptr);
// A frame read from an OpenEXR file (RGB or RGBA; its string attributes in metadata).
SkyFrame loadExr(const std::string& path);

}  // namespace firmament
