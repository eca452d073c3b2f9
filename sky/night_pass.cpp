#include "sky/night_pass.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "astro/sun.h"
#include "astro/time.h"
#include "atmosphere/atmosphere_block.h"
#include "atmosphere/atmosphere_spectra.h"
#include "common/moon_disc.glsl"
#include "common/night_sky.glsl"
#include "core/color.h"
#include "core/error.h"
#include "core/spectrum.h"
#include "sky/frame_light.h"
#include "sky/render_plan.h"
#include "sky/scene_view.h"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// std140 mirror of NightBlock in shaders/night/night_sky.comp.
struct NightBlock {
  float moonDirection[4];
  float sunFromMoon[4];
  float moonColour[4];
  float airglowRgb[4][4];
  float solarRgb[4];
  float enuToEcliptic[3][4];
  float enuToGalactic[3][4];
  float scatteredRgb[4];
  int32_t flags[4];
};
static_assert(sizeof(NightBlock) == 16 * 16);

void put(float (&out)[4], const glm::dvec3& v, double w = 0.0) {
  out[0] = float(v.x);
  out[1] = float(v.y);
  out[2] = float(v.z);
  out[3] = float(w);
}

astro::GeodeticLocation sceneLocation(const Scene& scene) {
  return astro::GeodeticLocation::fromDegrees(scene.number("/location/latitude_deg"),
                                              scene.number("/location/longitude_deg"),
                                              scene.number("/location/height_m"));
}

// Rec.709 of a spectrum given per 1-nm band over 360-830 nm.
template <typename F>
glm::dvec3 rec709Of(F spectralRadiance) {
  TabulatedSpectrum s;
  s.firstWavelength = kSpectrumMinNm;
  s.spacing = 1.0;
  for (double l = kSpectrumMinNm; l <= kSpectrumMaxNm + 1e-9; l += 1.0) s.values.push_back(spectralRadiance(l));
  return spectrumToLinearRec709(s);
}

// The angular size of a pixel near the image centre (rad).
double pixelAngle(const shared::CameraParameters& camera) {
  if (camera.projection == shared::kProjectionEquirectangular) return 2.0 * kPi / camera.width;
  if (camera.projection == shared::kProjectionFisheye) return camera.fov / camera.width;
  return 2.0 * std::tan(0.5 * camera.fov) / camera.width;
}

}  // namespace

const astro::StarCatalogue* nightStarCatalogue() {
  static std::once_flag once;
  static std::unique_ptr<astro::StarCatalogue> catalogue;
  std::call_once(once, [] {
    try {
      catalogue = std::make_unique<astro::StarCatalogue>(astro::loadDefaultStarCatalogue());
    } catch (const InputError&) {
      catalogue.reset();
    }
  });
  return catalogue.get();
}

namespace {

// The daytime Moon: the disc alone when the Moon is above the horizon and in the view.
void decideDayMoonDisc(const Scene& scene, const NightOptions& options, const astro::AstroTime& time,
                       const astro::GeodeticLocation& location, NightDecision& d) {
  if (!options.moonDisc) {
    d.dayMoonDiscReason = "switched off";
    return;
  }
  const astro::MoonLight moon = astro::moonLight(time, location);
  d.moonAltitudeDeg = 90.0 - moon.zenith / kDegree;
  char text[200];
  if (d.moonAltitudeDeg <= -1.0) {
    std::snprintf(text, sizeof(text), "the Moon is %.1f deg below the horizon", -d.moonAltitudeDeg);
    d.dayMoonDiscReason = text;
    return;
  }
  const shared::CameraParameters camera = makeSceneView(scene).camera;
  const PixelRect rect = moonDiscPixelRect(camera, moon.directionEnu, moon.angularRadius);
  if (rect.empty()) {
    std::snprintf(text, sizeof(text), "the Moon (%.1f deg high, azimuth %.1f deg) is outside the view",
                  d.moonAltitudeDeg, moon.azimuth / kDegree);
    d.dayMoonDiscReason = text;
    return;
  }
  d.dayMoonDisc = true;
  std::snprintf(text, sizeof(text),
                "the daytime Moon, %.1f deg high and %.0f %% lit, is in the view: its disc alone over %d x %d pixels",
                d.moonAltitudeDeg, 100.0 * moon.illuminatedFraction, rect.width(), rect.height());
  d.dayMoonDiscReason = text;
}

}  // namespace

NightDecision decideNight(const Scene& scene, const NightOptions& options, bool skyView) {
  NightDecision d;
  if (!options.enabled) {
    d.reason = "the night passes are switched off";
    return d;
  }
  if (scene.hasSection("sun")) {
    d.reason = "the scene's sun section gives the sun without a time: no Moon or stars to place";
    return d;
  }
  const astro::AstroTime time = astro::makeAstroTime(scene.string("/time/utc"));
  const astro::GeodeticLocation location = sceneLocation(scene);
  d.sunAltitudeDeg = astro::sunPosition(time, location).elevation() / kDegree;
  char text[160];
  if (d.sunAltitudeDeg >= options.sunAltitudeLimitDeg) {
    std::snprintf(text, sizeof(text), "the sun is %.1f deg above the horizon (the night runs below %.0f deg)",
                  d.sunAltitudeDeg, options.sunAltitudeLimitDeg);
    d.reason = text;
    decideDayMoonDisc(scene, options, time, location, d);
    return d;
  }
  std::snprintf(text, sizeof(text), "the sun is at %.1f deg (below %.0f deg)", d.sunAltitudeDeg,
                options.sunAltitudeLimitDeg);
  d.reason = text;
  const astro::MoonLight moon = astro::moonLight(time, location);
  d.moonAltitudeDeg = 90.0 - moon.zenith / kDegree;
  d.run = true;
  d.skyGlow = options.skyGlow;
  d.moonDisc = options.moonDisc && d.moonAltitudeDeg > -1.0;
  d.moonSky = options.moonSky && skyView && d.moonAltitudeDeg > kMoonSkyAltitudeLimitDeg;
  if (!options.moonSky)
    d.moonSkyReason = "switched off";
  else if (!skyView)
    d.moonSkyReason = "the moonlit sky is a second sky-view table: this frame marches per pixel or reads the 4D tables";
  else if (!d.moonSky) {
    std::snprintf(text, sizeof(text), "the Moon is %.1f deg below the horizon (lights the sky above %.0f deg)",
                  -d.moonAltitudeDeg, kMoonSkyAltitudeLimitDeg);
    d.moonSkyReason = text;
  }
  d.stars = options.stars && nightStarCatalogue() != nullptr;
  if (!options.stars)
    d.starsReason = "switched off";
  else if (!d.stars)
    d.starsReason = "no star catalogue at " + astro::defaultStarCataloguePath().string() +
                    " (Debian package xplanet, or $FIRMAMENT_STAR_CATALOGUE)";
  return d;
}

void planNight(const NightDecision& d, RenderPlan& plan) {
  if (!d.run) {
    plan.omitted.push_back({"night/moon_sky_view, night/night_sky", d.reason});
    if (d.dayMoonDisc)
      plan.passes.push_back({"night/moon_disc_day", "the Moon's disc added to the sky image over its pixels (cd/m^2)",
                             d.dayMoonDiscReason + ", extincted along the view", true});
    else if (!d.dayMoonDiscReason.empty())
      plan.omitted.push_back({"night/moon_disc_day", d.dayMoonDiscReason});
    return;
  }
  if (d.moonSky)
    plan.passes.push_back({"night/moon_sky_view (sky/sky_view_lut)", "sky-view table lit by the Moon, Rec.709",
                           "the Moon as the atmosphere's second light: the same tables, its direction and spectrum",
                           true});
  else
    plan.omitted.push_back({"night/moon_sky_view", d.moonSkyReason});
  std::string parts;
  if (d.moonSky) parts += "moonlit sky and ground";
  if (d.moonDisc) parts += std::string(parts.empty() ? "" : ", ") + "the Moon's disc";
  if (d.stars) parts += std::string(parts.empty() ? "" : ", ") + "stars (splatted on the CPU)";
  if (d.skyGlow) parts += std::string(parts.empty() ? "" : ", ") + "airglow, zodiacal light, faint stars";
  plan.passes.push_back({"night/night_sky", "the night's light added to the sky image (cd/m^2)",
                         d.reason + ": " + parts + ", extincted along the view", true});
  if (!d.stars) plan.omitted.push_back({"night stars", d.starsReason});
}

double pixelSolidAngle(const shared::CameraParameters& camera, glm::dvec2 p) {
  const double w = camera.width, h = camera.height;
  if (camera.projection == shared::kProjectionEquirectangular) {
    const double latitude = (0.5 - p.y / h) * kPi;
    return (2.0 * kPi / w) * (kPi / h) * std::cos(latitude);
  }
  const glm::dvec2 xy = shared::cameraImagePlane(camera, p);
  if (camera.projection == shared::kProjectionFisheye) {
    const double theta = glm::length(xy) * 0.5 * camera.fov;
    const double step = camera.fov / w;  // equidistant: angle per pixel
    return step * step * (theta > 1e-9 ? std::sin(theta) / theta : 1.0);
  }
  const double t = std::tan(0.5 * camera.fov);
  const double x = xy.x * t, y = xy.y * t;
  const double cosine = 1.0 / std::sqrt(1.0 + x * x + y * y);
  const double side = 2.0 * t / w;
  return side * side * cosine * cosine * cosine;
}

double addedIlluminance(const shared::CameraParameters& camera, const float* withRgba, const float* withoutRgba) {
  double sum = 0.0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const size_t i = (size_t(y) * camera.width + x) * 4;
      sum += (luminanceRec709(withRgba + i) - luminanceRec709(withoutRgba + i)) *
             pixelSolidAngle(camera, glm::dvec2(x + 0.5, y + 0.5));
    }
  return sum;
}

namespace {

// splatPointLights into the pixels of `rect` (an image of rect's size, row by row).
void splatInto(const shared::CameraParameters& camera, const std::vector<PointLight>& lights, const PixelRect& rect,
               std::vector<float>& image) {
  const int w = camera.width, h = camera.height;
  const bool wrap = camera.projection == shared::kProjectionEquirectangular;
  for (const PointLight& light : lights) {
    bool valid = false;
    const glm::dvec2 p = shared::cameraPixelOfDirection(camera, light.directionEnu, valid);
    if (!valid) continue;
    const double fx = p.x - 0.5, fy = p.y - 0.5;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const double ax = fx - x0, ay = fy - y0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        int x = x0 + i;
        const int y = y0 + j;
        if (wrap) x = ((x % w) + w) % w;
        if (x < 0 || x >= w || y < 0 || y >= h) continue;
        if (x < rect.x0 || x >= rect.x1 || y < rect.y0 || y >= rect.y1) continue;
        const double weight = (i ? ax : 1.0 - ax) * (j ? ay : 1.0 - ay);
        if (weight <= 0.0) continue;
        if (!shared::cameraSeesPixel(camera, glm::dvec2(x + 0.5, y + 0.5))) continue;
        const double radiance = weight / pixelSolidAngle(camera, glm::dvec2(x + 0.5, y + 0.5));
        float* out = &image[(size_t(y - rect.y0) * size_t(rect.width()) + size_t(x - rect.x0)) * 4];
        for (int c3 = 0; c3 < 3; ++c3) out[c3] += float(light.rgbLux[c3] * radiance);
      }
  }
}

}  // namespace

std::vector<float> splatPointLights(const shared::CameraParameters& camera, const std::vector<PointLight>& lights) {
  std::vector<float> image(size_t(camera.width) * size_t(camera.height) * 4, 0.0f);
  splatInto(camera, lights, PixelRect{0, 0, camera.width, camera.height}, image);
  return image;
}

glm::dvec3 moonRec709UnitLuminance() {
  static const glm::dvec3 colour = [] {
    const glm::dvec3 rgb =
        rec709Of([](double l) { return solarIrradianceTopOfAtmosphere()(l) * astro::lunarRelativeReflectance(l); });
    return rgb / luminanceRec709(rgb.x, rgb.y, rgb.z);
  }();
  return colour;
}

PixelRect moonDiscPixelRect(const shared::CameraParameters& camera, const glm::dvec3& moonDirection,
                            double angularRadius) {
  PixelRect rect;
  const double radius = angularRadius + 2.0 * pixelAngle(camera);
  // Two unit vectors across the Moon's direction span the circle around it.
  const glm::dvec3 m = glm::normalize(moonDirection);
  const glm::dvec3 a = glm::normalize(glm::cross(m, std::fabs(m.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 b = glm::cross(m, a);
  double lo[2] = {1e30, 1e30}, hi[2] = {-1e30, -1e30};
  bool any = false;
  constexpr int kPoints = 32;
  for (int k = 0; k <= kPoints; ++k) {
    const double t = 2.0 * kPi * k / kPoints;
    const glm::dvec3 d =
        k == kPoints ? m : std::cos(radius) * m + std::sin(radius) * (std::cos(t) * a + std::sin(t) * b);
    bool valid = false;
    const glm::dvec2 p = shared::cameraPixelOfDirection(camera, d, valid);
    if (!valid) continue;
    any = true;
    lo[0] = std::min(lo[0], p.x), lo[1] = std::min(lo[1], p.y);
    hi[0] = std::max(hi[0], p.x), hi[1] = std::max(hi[1], p.y);
  }
  if (!any) return rect;
  // The equirectangular image wraps: a circle across its seam spans the whole width.
  if (camera.projection == shared::kProjectionEquirectangular && hi[0] - lo[0] > 0.5 * camera.width) {
    lo[0] = 0.0;
    hi[0] = camera.width;
  }
  // A point of the circle near 90 deg from a perspective camera's axis projects millions of pixels out:
  // clamp to just outside the image before converting (an int overflow otherwise).
  const double w = camera.width, h = camera.height;
  rect.x0 = std::max(0, int(std::floor(std::clamp(lo[0], -2.0, w + 2.0))) - 1);
  rect.y0 = std::max(0, int(std::floor(std::clamp(lo[1], -2.0, h + 2.0))) - 1);
  rect.x1 = std::min(camera.width, int(std::ceil(std::clamp(hi[0], -2.0, w + 2.0))) + 1);
  rect.y1 = std::min(camera.height, int(std::ceil(std::clamp(hi[1], -2.0, h + 2.0))) + 1);
  if (rect.empty()) rect = PixelRect{};
  return rect;
}

std::vector<float> moonDiscAboveAir(const shared::CameraParameters& camera, const astro::MoonLight& moon,
                                    const PixelRect& rect) {
  std::vector<float> image(size_t(std::max(rect.width(), 0)) * size_t(std::max(rect.height(), 0)) * 4, 0.0f);
  if (rect.empty()) return image;
  const glm::dvec3 colour = moonRec709UnitLuminance();
  if (moon.angularRadius / pixelAngle(camera) < 2.0) {
    splatInto(camera, {{moon.directionEnu, colour * moon.illuminanceLux}}, rect, image);
    return image;
  }
  for (int y = rect.y0; y < rect.y1; ++y)
    for (int x = rect.x0; x < rect.x1; ++x) {
      double sum = 0.0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          bool valid = false;
          const glm::dvec3 d =
              shared::cameraRayDirection(camera, glm::dvec2(x + (i + 0.5) / 4.0, y + (j + 0.5) / 4.0), valid);
          if (!valid) continue;
          sum += shared::moonDiscRadiance(d, moon.directionEnu, moon.sunFromMoonEnu, moon.angularRadius,
                                          moon.litRadianceScale, moon.earthshineLuminance, 1.0);
        }
      float* out = &image[(size_t(y - rect.y0) * size_t(rect.width()) + size_t(x - rect.x0)) * 4];
      for (int c = 0; c < 3; ++c) out[c] = float(colour[c] * sum / 16.0);
    }
  return image;
}

DayMoonDiscPass::DayMoonDiscPass(gpu::Context& context)
    : context_(context),
      pipeline_(context,
                {"night/moon_disc_day",
                 {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer,
                  gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer},
                 sizeof(gpu::TileDispatch) + 4 * sizeof(int32_t)}) {}

bool DayMoonDiscPass::record(const Inputs& in, gpu::CommandList& commands) {
  const Scene& scene = *in.scene;
  moon_ = astro::moonLight(astro::makeAstroTime(scene.string("/time/utc")), sceneLocation(scene));
  rect_ = moonDiscPixelRect(in.camera, moon_.directionEnu, moon_.angularRadius);
  if (rect_.empty()) return false;
  const std::vector<float> above = moonDiscAboveAir(in.camera, moon_, rect_);
  const VkDeviceSize bytes = VkDeviceSize(above.size() * sizeof(float));
  if (!radiance_ || radiance_->size() < bytes)
    radiance_ = std::make_unique<gpu::Buffer>(context_, bytes, gpu::BufferUsage::Storage, gpu::MemoryLocation::Host,
                                              "daytime Moon disc");
  radiance_->upload(above);
  struct {
    gpu::TileDispatch tiles;
    int32_t rect[4];
  } push{};
  push.tiles = gpu::tileDispatch(context_, uint32_t(rect_.width()), uint32_t(rect_.height()));
  push.rect[0] = rect_.x0;
  push.rect[1] = rect_.y0;
  push.rect[2] = in.camera.width;
  const AtmosphereLuts& luts = *in.luts;
  commands.barrier();
  commands.bind(
      pipeline_,
      {luts.atmosphereBlock(), {luts.sunRadiance(), luts.linearClamp()}, *in.output, *in.frameBlock, *radiance_});
  commands.pushConstants(push);
  commands.dispatchTiles(push.tiles, "night/moon_disc_day");
  return true;
}

NightPass::NightPass(gpu::Context& context)
    : context_(context),
      skyViewPipeline_(
          context, {"sky/sky_view_lut",
                    {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
                     gpu::BindingType::StorageImage, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage},
                    4 * sizeof(float)}),
      nightPipeline_(
          context, {"night/night_sky",
                    {gpu::BindingType::UniformBuffer, gpu::BindingType::SampledImage, gpu::BindingType::SampledImage,
                     gpu::BindingType::StorageBuffer, gpu::BindingType::UniformBuffer, gpu::BindingType::UniformBuffer,
                     gpu::BindingType::StorageBuffer},
                    sizeof(gpu::TileDispatch)}),
      nightBlock_(context, sizeof(NightBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host, "night block") {}

void NightPass::record(const Inputs& in, gpu::CommandList& commands) {
  const Scene& scene = *in.scene;
  const NightDecision& d = *in.decision;
  const AtmosphereLuts& luts = *in.luts;
  const astro::AstroTime time = astro::makeAstroTime(scene.string("/time/utc"));
  const astro::GeodeticLocation location = sceneLocation(scene);
  moon_ = astro::moonLight(time, location);
  const shared::CameraParameters& camera = in.camera;
  const shared::AtmosphereParameters& geometry = luts.parameters();

  // The Moon's sky-view table: each batch's block with its conversions to Rec.709 times the Moon's
  // spectral irradiance over the tables' solar irradiance at the batch's wavelengths (linear in the light).
  if (!moonSkyView_ || int(moonSkyView_.width()) != in.skyViewWidth || int(moonSkyView_.height()) != in.skyViewHeight)
    moonSkyView_ = gpu::Image(context_, {uint32_t(in.skyViewWidth), uint32_t(in.skyViewHeight), 1, gpu::Format::RGBA32F,
                                         true, true, "moon sky-view LUT"});
  if (d.moonSky) {
    const std::vector<SpectralBatch> spectra =
        spectralBatches(in.lutSettings->spectralSamples, in.lutSettings->wavelengthsNm);
    FrameLight moonAlone;  // the Moon's spectrum at the batches' wavelengths, carrying only itself
    moonAlone.moon = true;
    moonAlone.channelScale = moonChannelScale(moon_, spectra, in.solarIrradianceScale);
    uploadLightBlocks(context_, luts, spectra, moonAlone, moonBlocks_);
    for (size_t b = 0; b < luts.batchCount(); ++b) {
      const AtmosphereLuts::Batch& batch = luts.batch(b);
      struct {
        float cameraRadius;
        float muS;
        int32_t steps;
        int32_t accumulate;
      } push{float(in.cameraRadius), float(moon_.directionEnu.z), in.viewSteps, b > 0 ? 1 : 0};
      commands.bind(skyViewPipeline_, {moonBlocks_[b],
                                       {batch.transmittance, luts.linearClamp()},
                                       {batch.multipleScattering, luts.linearClamp()},
                                       moonSkyView_,
                                       {*in.skyIrradiance[b], luts.linearClamp()},
                                       {batch.multipleScatteringAnisotropy, luts.linearClamp()}});
      commands.pushConstants(push);
      commands.dispatch(uint32_t((in.skyViewWidth + 7) / 8), uint32_t((in.skyViewHeight + 7) / 8), 1,
                        "night/moon_sky_view");
      commands.barrier();
    }
  }

  // The block: the Moon's disc, the sky's own light, the frames.
  NightBlock block{};
  const glm::dvec3 moonColour = moonRec709UnitLuminance();
  const double discPixels = moon_.angularRadius / pixelAngle(camera);
  const bool disc = d.moonDisc && discPixels >= 2.0;
  put(block.moonDirection, moon_.directionEnu, moon_.angularRadius);
  put(block.sunFromMoon, moon_.sunFromMoonEnu, moon_.litRadianceScale);
  put(block.moonColour, moonColour, moon_.earthshineLuminance);
  const double observer = in.cameraRadius;
  const double planet = geometry.bottom_radius;
  struct Line {
    double rayleigh, nm, height;
  };
  const Line lines[3] = {{shared::kAirglowOI5577Rayleigh, 557.7, shared::kAirglowOI5577HeightM},
                         {shared::kAirglowNaDRayleigh, 589.3, shared::kAirglowNaDHeightM},
                         {shared::kAirglowOI6300Rayleigh, 630.0, shared::kAirglowOI6300HeightM}};
  glm::dvec3 airglow[4];
  for (int k = 0; k < 3; ++k) {
    airglow[k] = rec709Of([&](double l) {
      double v = shared::airglowLineInBand(lines[k].rayleigh, lines[k].nm, l, 1.0);
      if (k == 2) v += shared::airglowLineInBand(shared::kAirglowOI6364Rayleigh, 636.4, l, 1.0);
      return v;
    });
    put(block.airglowRgb[k], airglow[k], planet + lines[k].height);
  }
  airglow[3] = rec709Of([](double l) { return shared::rayleighToRadiance(shared::kAirglowContinuumRayleighPerNm, l); });
  put(block.airglowRgb[3], airglow[3], planet + shared::kAirglowContinuumHeightM);
  const glm::dvec3 solar = rec709Of([](double l) { return solarIrradianceTopOfAtmosphere()(l); });
  put(block.solarRgb, solar, observer);
  const astro::NightSkyFrame frame = astro::nightSkyFrame(time, location);
  for (int i = 0; i < 3; ++i) {
    put(block.enuToEcliptic[i],
        glm::dvec3(frame.enuToSunEcliptic[0][i], frame.enuToSunEcliptic[1][i], frame.enuToSunEcliptic[2][i]));
    put(block.enuToGalactic[i],
        glm::dvec3(frame.enuToGalactic[0][i], frame.enuToGalactic[1][i], frame.enuToGalactic[2][i]));
  }
  // The light the air scatters of the sky's own light: an isotropic field keeps its radiance through a
  // conservatively scattering layer, so a view of transmittance T sees (1 - T) times the mean radiance
  // above the air (over the upper hemisphere, by solid angle) besides T times its own direction's.
  glm::dvec3 scattered(0.0);
  if (d.skyGlow) {
    double weights = 0.0;
    const int zenithSteps = 24, azimuthSteps = 24;
    for (int i = 0; i < zenithSteps; ++i) {
      const double cz = (i + 0.5) / zenithSteps;  // uniform in cos z: equal solid angle
      const double sz = std::sqrt(1.0 - cz * cz);
      for (int j = 0; j < azimuthSteps; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / azimuthSteps;
        const glm::dvec3 dir(sz * std::sin(phi), sz * std::cos(phi), cz);
        glm::dvec3 v(0.0);
        for (int k = 0; k < 4; ++k)
          v += airglow[k] * shared::vanRhijnFactor(cz, observer, double(block.airglowRgb[k][3]));
        v += solar * (shared::zodiacalSolarSpectrumFactor(frame.enuToSunEcliptic * dir) +
                      shared::stellarBackgroundSolarSpectrumFactor((frame.enuToGalactic * dir).z));
        scattered += v;
        weights += 1.0;
      }
    }
    scattered /= weights;
  }
  put(block.scatteredRgb, scattered, 2.0 * pixelAngle(camera));
  block.flags[0] = d.moonSky ? 1 : 0;
  block.flags[1] = disc ? 1 : 0;
  block.flags[2] = d.skyGlow ? 1 : 0;
  block.flags[3] = 1;
  nightBlock_.upload(&block, sizeof(block));

  // The stars (and a Moon too small to draw as a disc) as radiance above the air per pixel.
  std::vector<PointLight> points;
  if (d.stars) {
    const std::vector<astro::ApparentStar> stars = astro::apparentStars(*nightStarCatalogue(), time, location);
    for (const astro::ApparentStar& s : stars)
      if (s.directionEnu.z > -0.05) points.push_back({s.directionEnu, s.rgb});
  }
  starsDrawn_ = points.size();
  if (d.moonDisc && !disc) points.push_back({moon_.directionEnu, moonColour * moon_.illuminanceLux});
  const std::vector<float> starImage = splatPointLights(camera, points);
  const VkDeviceSize bytes = VkDeviceSize(starImage.size() * sizeof(float));
  if (!starFrame_ || starFrame_->size() != bytes)
    starFrame_ = std::make_unique<gpu::Buffer>(context_, bytes, gpu::BufferUsage::Storage, gpu::MemoryLocation::Host,
                                               "star frame");
  starFrame_->upload(starImage);

  commands.barrier();
  commands.bind(nightPipeline_, {luts.atmosphereBlock(),
                                 {luts.sunRadiance(), luts.linearClamp()},
                                 {d.moonSky ? moonSkyView_ : luts.sunRadiance(), luts.linearClamp()},
                                 *in.output,
                                 *in.frameBlock,
                                 nightBlock_,
                                 *starFrame_});
  commands.pushConstants(in.tiles);
  commands.dispatchTiles(in.tiles, "night/night_sky");
}

}  // namespace firmament
