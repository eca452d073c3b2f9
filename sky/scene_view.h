#pragma once
// What a renderer needs from a scene, resolved once: the atmosphere's parameters, the sun's
// direction (from time and place through astro/, or given directly), the camera's rays and its
// distance from the planet centre. The fast path and the reference both start from a SceneView, so
// they render the same view.
#include <glm/glm.hpp>
#include <string>

#include "atmosphere/atmosphere_settings.h"
#include "common/camera.glsl"
#include "core/scene.h"
#include "core/tonemap.h"

namespace firmament {

struct SceneView {
  AtmosphereSettings atmosphere;
  // Frame: the local East-North-Up axes of the ground point, origin at the planet centre; the
  // camera sits on the +z axis.
  glm::dvec3 sunDirection{0.0, 0.0, 1.0};
  double sunZenith = 0.0;      // rad (apparent, refraction included when computed from time)
  double sunAzimuth = 0.0;     // rad clockwise from north
  std::string sunSource;       // "time and location" or "scene sun section"
  double sunDistanceAu = 1.0;  // Earth-Sun distance (au): from the ephemeris, 1 with a scene sun section
  double cameraRadius = 0.0;   // m from the planet centre
  shared::CameraParameters camera{};
};

SceneView makeSceneView(const Scene& scene);

// The PNG preview's exposure and tone map from /camera/exposure.
ExposureSettings sceneExposure(const Scene& scene);

}  // namespace firmament
