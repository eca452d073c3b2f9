#pragma once
// The night in the frame (docs/night.md, "The night in the frame"): the Moon as the atmosphere's second
// light (the sky-view table marched again with the Moon's direction and spectrum), the Moon's disc, the
// stars and the sky's own light (airglow, zodiacal light, faint stars), added to the sky frame before
// the clouds composite over it. Which parts a scene needs: sky/night_plan.h.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "astro/moon_photometry.h"
#include "astro/night_sky.h"
#include "astro/star_catalogue.h"
#include "atmosphere/atmosphere_luts.h"
#include "common/camera.glsl"
#include "core/scene.h"
#include "gpu/command.h"
#include "gpu/dispatch.h"
#include "gpu/pipeline.h"
#include "sky/night_plan.h"

namespace firmament {

// The stars (and a Moon smaller than two pixels) as radiance per pixel above the air, RGBA floats: each
// star's illuminance is split bilinearly over the four pixels around its image point and divided by each
// pixel's solid angle, so the pixels' sum of radiance x solid angle is the star's illuminance at any
// resolution (inside the image).
struct PointLight {
  glm::dvec3 directionEnu;
  glm::dvec3 rgbLux;  // Rec.709 whose luminance is the illuminance (lux) above the air
};
std::vector<float> splatPointLights(const shared::CameraParameters& camera, const std::vector<PointLight>& lights);
// The solid angle (sr) of the pixel centred at `pixelCentre` (pixel units) for the camera's projection.
double pixelSolidAngle(const shared::CameraParameters& camera, glm::dvec2 pixelCentre);
// The illuminance (lx) a term adds to a frame: the sum over the image of (luminance of `with` minus
// `without`, both RGBA cd/m^2 of this camera's size) x the pixel's solid angle.
double addedIlluminance(const shared::CameraParameters& camera, const float* withRgba, const float* withoutRgba);

// The pixels the Moon's disc can touch: its circle of angular radius plus two pixels projected, clamped
// to the image; empty when the Moon is out of the view. x1, y1 are one past the last.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};
PixelRect moonDiscPixelRect(const shared::CameraParameters& camera, const glm::dvec3& moonDirection,
                            double angularRadius);
// The Moon's disc above the air over `rect`, RGBA floats (cd/m^2, Rec.709), row by row: moonDiscRadiance
// with 4x4 samples per pixel when the disc is at least two pixels in radius, else the Moon's illuminance
// splatted as a point (splatPointLights), as the night pass draws it.
std::vector<float> moonDiscAboveAir(const shared::CameraParameters& camera, const astro::MoonLight& moon,
                                    const PixelRect& rect);
// The Moon's colour: Rec.709 of unit luminance of the solar spectrum times the lunar relative reflectance.
glm::dvec3 moonRec709UnitLuminance();

// The daytime Moon (docs/night.md, "The daytime Moon"): the disc alone, over its pixel rectangle, extincted
// along the view (shaders/night/moon_disc_day.comp), for frames with the sun above the night's limit.
class DayMoonDiscPass {
 public:
  explicit DayMoonDiscPass(gpu::Context& context);
  struct Inputs {
    const Scene* scene = nullptr;
    const AtmosphereLuts* luts = nullptr;
    const gpu::Buffer* frameBlock = nullptr;
    gpu::Buffer* output = nullptr;
    shared::CameraParameters camera{};
  };
  // Records nothing (and returns false) when the disc's rectangle is empty.
  bool record(const Inputs& inputs, gpu::CommandList& commands);
  const astro::MoonLight& moon() const { return moon_; }
  const PixelRect& rect() const { return rect_; }

 private:
  gpu::Context& context_;
  gpu::ComputePipeline pipeline_;
  std::unique_ptr<gpu::Buffer> radiance_;
  astro::MoonLight moon_;
  PixelRect rect_;
};

// The GPU side: the Moon's sky-view table and the per-pixel pass (shaders/night/night_sky.comp).
class NightPass {
 public:
  explicit NightPass(gpu::Context& context);
  struct Inputs {
    const Scene* scene = nullptr;
    const NightDecision* decision = nullptr;
    const AtmosphereLuts* luts = nullptr;
    const AtmosphereLutSettings* lutSettings = nullptr;
    std::vector<const gpu::Image*> skyIrradiance;  // the ground's skylight table per spectral batch
    const gpu::Buffer* frameBlock = nullptr;
    gpu::Buffer* output = nullptr;
    gpu::TileDispatch tiles{};
    shared::CameraParameters camera{};
    double cameraRadius = 0.0;
    double solarIrradianceScale = 1.0;  // the Sun's distance factor in the tables' solar irradiance
    int viewSteps = 32, skyViewWidth = 192, skyViewHeight = 108;
  };
  void record(const Inputs& inputs, gpu::CommandList& commands);
  const astro::MoonLight& moon() const { return moon_; }
  size_t starsDrawn() const { return starsDrawn_; }

 private:
  gpu::Context& context_;
  gpu::ComputePipeline skyViewPipeline_;
  gpu::ComputePipeline nightPipeline_;
  std::vector<gpu::Buffer> moonBlocks_;  // per spectral batch: the batch's block, Moon-scaled conversions
  gpu::Buffer nightBlock_;
  std::unique_ptr<gpu::Buffer> starFrame_;
  gpu::Image moonSkyView_;
  astro::MoonLight moon_;
  size_t starsDrawn_ = 0;
};

// The star catalogue, read once (null when it is not installed: the stars are then left out).
const astro::StarCatalogue* nightStarCatalogue();

}  // namespace firmament
