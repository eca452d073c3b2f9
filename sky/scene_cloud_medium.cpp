#include "sky/scene_cloud_medium.h"

#include "clouds/cloud_settings.h"
#include "gpu/command.h"
#include "sky/scene_weather.h"

namespace firmament {

bool sceneHasCloudLayers(const Scene& scene) {
  return scene.hasSection("clouds") && !scene.at("/clouds/layers").empty();
}

double sceneGroundRadius(const Scene& scene, const SceneView& view) {
  return view.cameraRadius - scene.number("/camera/height_above_ground_m");
}

CloudMedium sceneCloudMedium(const Scene& scene, const SceneView& view, gpu::Context& context,
                             const CloudNoiseSettings& noiseSettings) {
  const CloudSettings clouds = CloudSettings::fromScene(scene);
  CloudNoise noise(context);
  gpu::CommandList commands(context);
  noise.update(clouds.seed, noiseSettings, commands);
  commands.submitAndWait();
  const double ground = sceneGroundRadius(scene, view);
  return CloudMedium(sharedCloudLayers(clouds, ground), noise.downloadShape(), noise.downloadDetail(),
                     noise.downloadCurl(), cloudWeatherMapForScene(scene), ground);
}

CloudMedium emptyCloudMedium(double groundRadius_m) {
  return CloudMedium({}, NoiseVolume{}, NoiseVolume{}, NoiseVolume{}, CloudWeatherMap{}, groundRadius_m);
}

}  // namespace firmament
