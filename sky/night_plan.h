#pragma once
// Which parts of the night a scene needs (docs/night.md, "The night in the frame"): only scenes whose sun,
// from the scene's time and place, is below kNightSunAltitudeLimitDeg run any night pass.
#include <string>

#include "core/scene.h"

namespace firmament {

struct RenderPlan;

// Above this sun altitude no night pass runs. Measured (docs/night.md, "Where the night starts"): the
// night's sky terms change no pixel by more than 2.1e-6 there (2.5e-5 at 0 deg). The Moon's disc is not
// negligible in daylight: above it the disc alone is drawn (`NightDecision::dayMoonDisc`, the daytime Moon).
inline constexpr double kNightSunAltitudeLimitDeg = 10.0;
// The Moon lights the sky while its apparent altitude is above this (a choice; the step it leaves in a
// 24 h sweep is still to be measured).
inline constexpr double kMoonSkyAltitudeLimitDeg = -5.0;

// What the renderer's options say about the night.
struct NightOptions {
  bool enabled = true;                                                 // false: no night pass at all
  double sunAltitudeLimitDeg = kNightSunAltitudeLimitDeg;              // the night runs below this sun altitude
  bool moonSky = true, moonDisc = true, skyGlow = true, stars = true;  // each part (tests switch them)
};

// Which parts of the night a scene needs, and why (what `render --explain` prints).
struct NightDecision {
  bool run = false;  // any part
  bool moonSky = false, moonDisc = false, skyGlow = false, stars = false;
  // The daytime Moon: with the sun above the limit (no night pass, `run` false) the disc alone, over its
  // pixel rectangle, when the Moon is above the horizon and in the view (night/moon_disc_day).
  bool dayMoonDisc = false;
  std::string dayMoonDiscReason;           // why it runs or not (with the sun above the limit)
  std::string reason;                      // why the night runs or not
  std::string moonSkyReason, starsReason;  // why those parts are left out, when they are
  double sunAltitudeDeg = 0.0, moonAltitudeDeg = 0.0;
};
// `skyView`: the frame reads the sky-view table (the moonlit sky is a second such table).
NightDecision decideNight(const Scene& scene, const NightOptions& options, bool skyView);
// Adds the night's passes, or their omission with the reason, to a plan.
void planNight(const NightDecision& night, RenderPlan& plan);

}  // namespace firmament
