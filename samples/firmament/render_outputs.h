#pragma once
// What `firmament render` writes for one frame: <out>.exr (linear Rec.709, cd/m²), <out>.png (preview with
// the scene's exposure and tone map) and <out>.json (device, per-pass GPU timings, sun, luminance
// statistics), each atomically. The renderer (sky/) writes no files; the tool does.
#include <string>

#include "core/scene.h"
#include "core/tonemap.h"
#include "sky/sky_renderer.h"

namespace firmament::cli {

// Returns the EV100 used for the preview. In a sequence, `adaptation` carries the auto exposure's adapted
// luminance from frame to frame (/camera/exposure/temporal_adaptation), `dtSeconds` after the last frame.
double writeRenderOutputs(const std::string& exrPath, const Scene& scene, const RenderResult& result,
                          const std::string& deviceDescription, ExposureAdaptation* adaptation = nullptr,
                          double dtSeconds = 0.0);

}  // namespace firmament::cli
