#pragma once
// What `firmament render` writes for one frame: <out>.exr (linear Rec.709, cd/m²), <out>.png (preview with
// the scene's exposure and tone map) and <out>.json (device, per-pass GPU timings, sun, luminance
// statistics), each atomically. The renderer writes no files; the tool does, from the public API's frame.
#include <string>

#include "firmament/image.h"
#include "firmament/sky.h"

namespace firmament::cli {

// Returns the EV100 used for the preview. In a sequence, `adaptation` carries the auto exposure's adapted
// luminance from frame to frame (/camera/exposure/temporal_adaptation), `dtSeconds` after the last frame.
double writeRenderOutputs(const std::string& exrPath, const SkyFrame& frame, const Exposure& exposure,
                          const std::string& deviceDescription, EyeAdaptation* adaptation = nullptr,
                          double dtSeconds = 0.0);

}  // namespace firmament::cli
