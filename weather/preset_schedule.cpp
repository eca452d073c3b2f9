#include "weather/preset_schedule.h"

#include <algorithm>

namespace firmament::weather {
namespace {
double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
}  // namespace

PresetSchedule::PresetSchedule(std::string initialPreset, std::vector<PresetChange> changes)
    : initial_(std::move(initialPreset)), changes_(std::move(changes)) {
  presetParameters(initial_);  // validates the name
  for (const auto& c : changes_) presetParameters(c.preset);
  std::stable_sort(changes_.begin(), changes_.end(),
                   [](const PresetChange& a, const PresetChange& b) { return a.at_s < b.at_s; });
}

PresetParameters PresetSchedule::parametersAt(double t_s) const {
  // Replay the changes up to t: each starts from the blend in effect at its start time.
  PresetParameters from = presetParameters(initial_), to = from;
  double start = 0.0, duration = 0.0;
  auto blendAt = [&](double t) {
    double s = duration > 0.0 ? smoothstep((t - start) / duration) : 1.0;
    return blend(from, to, s);
  };
  for (const auto& c : changes_) {
    if (c.at_s > t_s) break;
    from = blendAt(c.at_s);
    to = presetParameters(c.preset);
    start = c.at_s;
    duration = c.transition_s;
  }
  return blendAt(t_s);
}

const std::string& PresetSchedule::presetAt(double t_s) const {
  const std::string* name = &initial_;
  for (const auto& c : changes_)
    if (c.at_s <= t_s) name = &c.preset;
  return *name;
}

}  // namespace firmament::weather
