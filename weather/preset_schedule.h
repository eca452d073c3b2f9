#pragma once
// Preset changes over time. Each change blends from the parameters in effect at the moment it starts
// (the state of any unfinished transition is "baked", as seed 002 does with its weather-map texture) to
// the new preset with a smoothstep, so a change that interrupts another never makes a jump.
#include <string>
#include <vector>

#include "weather/weather_presets.h"

namespace firmament::weather {

struct PresetChange {
  double at_s = 0.0;  // model time the change starts
  std::string preset;
  double transition_s = 3600.0;  // blend duration; 0 = immediate switch
};

class PresetSchedule {
 public:
  PresetSchedule(std::string initialPreset, std::vector<PresetChange> changes);
  // The blended parameters at model time t (a pure function of t).
  PresetParameters parametersAt(double t_s) const;
  // The preset whose blend is most recent at t (for reports).
  const std::string& presetAt(double t_s) const;

 private:
  std::string initial_;
  std::vector<PresetChange> changes_;  // sorted by at_s
};

}  // namespace firmament::weather
