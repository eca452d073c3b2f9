#pragma once
// What `firmament render` writes for one frame: <out>.exr (linear Rec.709, cd/m²), <out>.png (preview with
// the scene's exposure and tone map) and <out>.json (device, per-pass GPU timings, sun, luminance
// statistics), each atomically. The renderer (sky/) writes no files; the tool does.
#include <string>

#include "core/scene.h"
#include "sky/sky_renderer.h"

namespace firmament::cli {

// Returns the EV100 used for the preview.
double writeRenderOutputs(const std::string& exrPath, const Scene& scene, const RenderResult& result,
                          const std::string& deviceDescription);

}  // namespace firmament::cli
