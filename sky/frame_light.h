#pragma once
// The light of the frame's clouds, terrain and aerial perspective (docs/night.md, "The Moon as the
// clouds' light"; decision 0228): the Sun, or at night the Moon. The light is whichever gives more
// horizontal illuminance at the camera's ground point, and it carries both lights' illuminance (its
// irradiance times (E_sun + E_moon) / E_chosen), so the ground's light is right in twilight and only the
// weaker light's direction is lost. The tables are linear in the light: the Moon is the tables' light with
// each spectral batch's Rec.709 conversions multiplied by the Moon's spectral irradiance over the tables'
// solar irradiance (astro::moonToSolarIrradianceRatio), as the night's moonlit sky does; nothing is
// recomputed.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "astro/moon_photometry.h"
#include "atmosphere/atmosphere_luts.h"
#include "atmosphere/atmosphere_spectra.h"
#include "gpu/buffer.h"
#include "gpu/image.h"

namespace firmament {

// The horizontal illuminance at the ground that the tables give for a light: the direct light
// E T(r, mu) mu (the transmittance table) plus the sky's (the ground's skylight table E_sky(r, mu)), each
// batch's channels times channelScale[b] (the light's spectral irradiance over the tables' solar
// irradiance), through the batches' Rec.709 conversions (direct: the sun's, sky: the sky's). The tables are
// read back from the GPU once (a 256 x 64 and a 64 x 16 RGBA32F table per batch).
class TableGroundIlluminance {
 public:
  TableGroundIlluminance(const AtmosphereLuts& luts, const std::vector<const gpu::Image*>& skyIrradiance,
                         const std::vector<SpectralBatch>& spectra);
  // lux on a horizontal surface at radius r (m) for a light of zenith cosine mu.
  double lux(double r, double mu, const std::vector<glm::dvec3>& channelScale) const;
  // The direct part alone (normal to the light, not times mu): lux.
  double directNormalLux(double r, double mu, const std::vector<glm::dvec3>& channelScale) const;

 private:
  struct Table {
    std::vector<float> texels;  // RGBA
    int width = 0, height = 0;
    glm::dvec3 at(glm::dvec2 uv) const;  // bilinear through texel centres, clamped
  };
  std::vector<Table> transmittance_, skylight_;
  std::vector<shared::AtmosphereParameters> parameters_;
  std::vector<SpectralBatch> spectra_;
};

// Per batch, the factor that turns the tables' solar irradiance into the Moon's (no sun-distance factor:
// the ratio includes both distances, so the tables' solarIrradianceScale is divided out).
std::vector<glm::dvec3> moonChannelScale(const astro::MoonLight& moon, const std::vector<SpectralBatch>& spectra,
                                         double solarIrradianceScale);

struct FrameLight {
  bool moon = false;                     // the Moon is the light; else the Sun
  glm::dvec3 direction{0.0, 0.0, 1.0};   // ENU, toward the light
  double sunGroundLux = 0.0;             // horizontal illuminance at the ground from the Sun, per the tables
  double moonGroundLux = 0.0;            // the same from the Moon (0 when the night does not run)
  double scale = 1.0;                    // (sun + moon) / the chosen light's: the chosen light carries both
  std::vector<glm::dvec3> channelScale;  // per batch: the light's spectral irradiance over the tables' solar
  std::string reason;                    // what `render` reports
};

// Below this ratio of the weaker light's ground illuminance to the stronger's, the weaker is left out
// (scale 1): the Sun's frame keeps its pixels unchanged with a Moon 1e4 times fainter.
inline constexpr double kFrameLightNegligibleRatio = 1e-4;

// The light from the two lights' ground illuminances (decision 0228).
FrameLight chooseFrameLight(double sunGroundLux, double moonGroundLux, const glm::dvec3& sunDirection,
                            const glm::dvec3& moonDirection);

// Per batch, the light's atmosphere block: the batch's parameters with its Rec.709 conversions times
// diag(channelScale[b]) times scale. `blocks` is resized to the batch count and uploaded.
void uploadLightBlocks(gpu::Context& context, const AtmosphereLuts& luts, const std::vector<SpectralBatch>& spectra,
                       const FrameLight& light, std::vector<gpu::Buffer>& blocks);

}  // namespace firmament
