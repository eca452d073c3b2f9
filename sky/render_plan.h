#pragma once
// A scene compiles to the list of passes it needs, and only those run: no clouds section, no noise
// textures, no cloud march, no shadow map. `firmament render --explain` prints the plan.
#include <string>
#include <vector>

#include "core/scene.h"

namespace firmament {

struct PlannedPass {
  std::string name;    // the pass and its shader, e.g. "atmosphere/transmittance_lut"
  std::string output;  // what it produces
  std::string reason;  // why this scene needs it
  bool perFrame = true;  // false: depends on parameters only, cached by their hash
};

struct OmittedPass {
  std::string name;
  std::string reason;
};

struct RenderPlan {
  std::vector<PlannedPass> passes;
  std::vector<OmittedPass> omitted;      // not needed by this scene
  std::vector<OmittedPass> unavailable;  // asked for by the scene, not implemented in this version
  bool has(const std::string& name) const;
};

RenderPlan planRender(const Scene& scene);

// Human-readable listing (for --explain).
std::string describePlan(const RenderPlan& plan);

}  // namespace firmament
