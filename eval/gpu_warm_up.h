#pragma once
// Warming a GPU up before timed renders. An idle GPU runs at low clocks (an H100 at 345 MHz), and
// the first renders after a pause would be timed at them; the benches render this long first.
// docs/gpu.md "Checking on a real GPU".

#include "core/scene.h"
#include "sky/sky_renderer.h"

namespace firmament {

constexpr double kGpuWarmUpSeconds = 0.5;

// Renders `scene` with `options` (images kept on the GPU) until kGpuWarmUpSeconds of wall time have
// passed, at most 20 renders. Nothing on a CPU device (lavapipe): its clocks are the CPU's.
void warmUpGpu(SkyRenderer& renderer, const Scene& scene, SkyRenderOptions options);

}  // namespace firmament
