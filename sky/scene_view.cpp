#include "sky/scene_view.h"

#include <cmath>

#include "astro/geodetic.h"
#include "astro/sun.h"
#include "astro/time.h"

namespace firmament {
namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;
constexpr double kAstronomicalUnit = 1.495978707e11;  // m (IAU 2012 Resolution B2)
}  // namespace

SceneView makeSceneView(const Scene& scene) {
  SceneView view;
  view.atmosphere = AtmosphereSettings::fromScene(scene);
  if (scene.hasSection("sun")) {
    view.sunZenith = scene.number("/sun/zenith_deg") * kDegree;
    view.sunAzimuth = scene.number("/sun/azimuth_deg") * kDegree;
    view.sunDirection = astro::enuDirection(view.sunZenith, view.sunAzimuth);
    view.sunSource = "scene sun section";
    view.sunDistanceAu = scene.number("/sun/distance_au");
    view.atmosphere.solarIrradianceScale = 1.0 / (view.sunDistanceAu * view.sunDistanceAu);
  } else {
    auto location = astro::GeodeticLocation::fromDegrees(scene.number("/location/latitude_deg"),
                                                         scene.number("/location/longitude_deg"),
                                                         scene.number("/location/height_m"));
    auto time = astro::makeAstroTime(scene.string("/time/utc"));
    auto sun = astro::sunPosition(time, location);
    view.sunZenith = sun.zenith;
    view.sunAzimuth = sun.azimuth;
    view.sunDirection = astro::enuDirection(sun.zenith, sun.azimuth);
    view.sunSource = "time and location";
    // The tabulated solar spectrum is at 1 au: scale the irradiance by (1 au / d)^2 for the date.
    view.sunDistanceAu = sun.distance / kAstronomicalUnit;
    view.atmosphere.solarIrradianceScale = 1.0 / (view.sunDistanceAu * view.sunDistanceAu);
  }
  // The ground sphere is at the location's height (atmosphereParametersAt); the camera is above it.
  view.cameraRadius =
      view.atmosphere.bottomRadius + view.atmosphere.groundHeight + scene.number("/camera/height_above_ground_m");

  shared::CameraParameters& c = view.camera;
  shared::cameraBasis(scene.number("/camera/yaw_deg") * kDegree, scene.number("/camera/pitch_deg") * kDegree,
                      scene.number("/camera/roll_deg") * kDegree, c.forward, c.right, c.up);
  c.fov = scene.number("/camera/fov_deg") * kDegree;
  c.yaw = scene.number("/camera/yaw_deg") * kDegree;
  const std::string projection = scene.string("/camera/projection");
  c.projection = projection == "fisheye"           ? shared::kProjectionFisheye
                 : projection == "equirectangular" ? shared::kProjectionEquirectangular
                                                   : shared::kProjectionPerspective;
  c.width = int(scene.integer("/camera/width"));
  c.height = int(scene.integer("/camera/height"));
  return view;
}

ExposureSettings sceneExposure(const Scene& scene) {
  ExposureSettings exposure;
  exposure.mode =
      scene.string("/camera/exposure/mode") == "fixed" ? ExposureSettings::Mode::Fixed : ExposureSettings::Mode::Auto;
  exposure.ev100 = scene.number("/camera/exposure/ev100");
  exposure.compensationEv = scene.number("/camera/exposure/compensation_ev");
  exposure.tonemap = scene.string("/camera/exposure/tonemap");
  return exposure;
}

}  // namespace firmament
