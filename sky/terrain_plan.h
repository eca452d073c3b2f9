#pragma once
// The terrain's entries in a scene's render plan (sky/render_plan.h, `render --explain`).
#include "core/scene.h"
#include "sky/render_plan.h"

namespace firmament {

// Adds the terrain's passes (the scene has a /terrain section and the f_ms path is used).
void addTerrainPasses(const Scene& scene, RenderPlan& plan);

}  // namespace firmament
