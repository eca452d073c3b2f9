#pragma once
// The public facade: a scene in, an HDR image out (linear Rec.709, cd/m²), with the pass plan and
// per-pass GPU timings. A host application keeps one SkyRenderer per Vulkan context; tables that
// depend only on parameters (atmosphere LUTs) are reused across frames.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_luts.h"
#include "atmosphere/fms_sky_irradiance.h"
#include "atmosphere/scattering_tables.h"
#include "core/image.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "gpu/dispatch.h"
#include "sky/render_plan.h"
#include "sky/scene_view.h"

namespace firmament {

struct SkyRenderOptions {
  AtmosphereLutSettings luts;
  MultipleScattering multipleScattering = MultipleScattering::HillaireFms;
  ScatteringTableSettings tables;              // BrunetonTables: orders (tables.scatteringOrders), sizes
  FmsSkyIrradianceSettings fmsSkyIrradiance;   // HillaireFms: the ground's skylight table
  int viewSteps = 32;  // march steps along each view ray
  gpu::DispatchOrder dispatchOrder = gpu::DispatchOrder::Auto;
};

struct RenderResult {
  Image image;
  RenderPlan plan;
  SceneView view;
  std::vector<gpu::PassTiming> timings;  // GPU time per pass (ms), in execution order
  double frameMilliseconds = 0.0;        // GPU time of the per-frame passes
  double precomputeMilliseconds = 0.0;   // GPU time of the tables (0 when cached)
  bool tablesReused = false;
  std::string timingNote;                // non-empty when timings are wall clock
};

class SkyRenderer {
 public:
  explicit SkyRenderer(gpu::Context& context);
  RenderResult render(const Scene& scene, const SkyRenderOptions& options = {});
  gpu::Context& context() { return context_; }

 private:
  gpu::Context& context_;
  AtmosphereLuts luts_;
  FmsSkyIrradiance fmsSkyIrradiance_;
  std::unique_ptr<ScatteringTables> tables_;  // created on first use (5 pipelines)
  gpu::ComputePipeline skyPipeline_;
  gpu::ComputePipeline skyTablesPipeline_;
  gpu::Buffer frameBlock_;
};

// Writes <out>.exr, <out>.png (preview with the scene's exposure) and <out>.json (stats), each
// atomically. Returns the EV100 used for the preview.
double writeRenderOutputs(const std::string& exrPath, const Scene& scene, const RenderResult& result,
                          const std::string& deviceDescription);

}  // namespace firmament
