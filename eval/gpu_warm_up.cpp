#include "eval/gpu_warm_up.h"

#include <chrono>

namespace firmament {

void warmUpGpu(SkyRenderer& renderer, const Scene& scene, SkyRenderOptions options) {
  if (renderer.context().isCpu()) return;
  constexpr int kMostRenders = 20;
  options.downloadImages = false;  // a download leaves the GPU idle (SkyRenderOptions::downloadImages)
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kMostRenders; ++i) {
    renderer.render(scene, options);
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= kGpuWarmUpSeconds) break;
  }
}

}  // namespace firmament
