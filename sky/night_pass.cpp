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

std::vector<float> splatPointLights(const shared::CameraParameters& camera, const std::vector<PointLight>& lights) {
  const int w = camera.width, h = camera.height;
  std::vector<float> image(size_t(w) * size_t(h) * 4, 0.0f);
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
        const double weight = (i ? ax : 1.0 - ax) * (j ? ay : 1.0 - ay);
        if (weight <= 0.0) continue;
        const shared::CameraParameters& c = camera;
        if (!shared::cameraSeesPixel(c, glm::dvec2(x + 0.5, y + 0.5))) continue;
        const double radiance = weight / pixelSolidAngle(camera, glm::dvec2(x + 0.5, y + 0.5));
        float* out = &image[(size_t(y) * size_t(w) + size_t(x)) * 4];
        for (int c3 = 0; c3 < 3; ++c3) out[c3] += float(light.rgbLux[c3] * radiance);
      }
  }
  return image;
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
  const glm::dvec3 moonColour = [] {
    const glm::dvec3 rgb =
        rec709Of([](double l) { return solarIrradianceTopOfAtmosphere()(l) * astro::lunarRelativeReflectance(l); });
    return rgb / luminanceRec709(rgb.x, rgb.y, rgb.z);
  }();
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
