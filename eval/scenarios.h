#pragma once
// The benchmark and calibration scenarios: scene files under eval/scenarios/<group>/ (clouds,
// calibration, atmosphere), built into the program (eval/CMakeLists.txt), with one index.json per group
// that lists the group's scenarios in order with what the scene file cannot say (a one-line description,
// whether --quick runs it, the reference's paths). Any of them renders as an ordinary scene:
//   firmament render eval/scenarios/clouds/cumulus_noon.json
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace firmament {

// The text of eval/scenarios/<path> ("clouds/cumulus_noon.json"); std::logic_error if it is not built in.
std::string_view evalScenarioText(const std::string& path);

// eval/scenarios/<group>/index.json, parsed.
nlohmann::json evalScenarioIndex(const std::string& group);

// eval/scenarios/<group>/<name>.json as a validated scene, with `overrides` applied
// (e.g. "/camera/width=32"). Named "eval/scenarios/<group>/<name>.json" in errors and metadata.
Scene evalScenarioScene(const std::string& group, const std::string& name,
                        const std::vector<std::string>& overrides = {});

// The paths of every built-in scenario file (index files included), sorted.
std::vector<std::string> evalScenarioPaths();

}  // namespace firmament
