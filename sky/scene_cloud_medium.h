#pragma once
// A scene's clouds as the CPU sees them (docs/clouds/reference.md and docs/clouds/vdb-export.md): the
// CloudMedium of clouds/reference_clouds.h with the scene's layers over the ground sphere below the
// camera, the noise textures baked on the GPU (lavapipe without one) and read back, and the same
// weather map as the fast path (sky/scene_weather.h). `firmament reference` and `firmament export-vdb`
// build their medium here, so both read the render's field.
#include "clouds/cloud_noise.h"
#include "clouds/reference_clouds.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "sky/scene_view.h"

namespace firmament {

// True when the scene has a clouds section with at least one layer (the fast path draws clouds).
bool sceneHasCloudLayers(const Scene& scene);

// Radius (m) of the ground sphere below the camera: the cloud frame's layers start from it.
double sceneGroundRadius(const Scene& scene, const SceneView& view);

// The medium of a scene with cloud layers (sceneHasCloudLayers); bakes the noise of the scene's seed
// on `context` and waits for it.
CloudMedium sceneCloudMedium(const Scene& scene, const SceneView& view, gpu::Context& context,
                             const CloudNoiseSettings& noise = {});

// A medium with no layers (extinction 0 everywhere) over the scene's ground sphere; needs no GPU.
CloudMedium emptyCloudMedium(double groundRadius_m);

}  // namespace firmament
