#include "sky/frame_light.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "atmosphere/atmosphere_block.h"
#include "common/atmosphere_lut.glsl"
#include "common/scattering_lut.glsl"
#include "core/color.h"

namespace firmament {

glm::dvec3 TableGroundIlluminance::Table::at(glm::dvec2 uv) const {
  const double x = std::clamp(uv.x * width - 0.5, 0.0, double(width - 1));
  const double y = std::clamp(uv.y * height - 0.5, 0.0, double(height - 1));
  const int x0 = std::min(int(x), width - 1), y0 = std::min(int(y), height - 1);
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const double ax = x - x0, ay = y - y0;
  auto texel = [&](int i, int j) {
    const float* t = &texels[(size_t(j) * size_t(width) + size_t(i)) * 4];
    return glm::dvec3(t[0], t[1], t[2]);
  };
  return (1.0 - ay) * ((1.0 - ax) * texel(x0, y0) + ax * texel(x1, y0)) +
         ay * ((1.0 - ax) * texel(x0, y1) + ax * texel(x1, y1));
}

TableGroundIlluminance::TableGroundIlluminance(const AtmosphereLuts& luts,
                                               const std::vector<const gpu::Image*>& skyIrradiance,
                                               const std::vector<SpectralBatch>& spectra)
    : spectra_(spectra) {
  if (skyIrradiance.size() != luts.batchCount() || spectra.size() != luts.batchCount())
    throw std::logic_error("TableGroundIlluminance: one skylight table and one spectral batch per batch");
  for (size_t b = 0; b < luts.batchCount(); ++b) {
    const gpu::Image& t = luts.batch(b).transmittance;
    transmittance_.push_back({t.downloadFloats(), int(t.width()), int(t.height())});
    const gpu::Image& s = *skyIrradiance[b];
    skylight_.push_back({s.downloadFloats(), int(s.width()), int(s.height())});
    parameters_.push_back(luts.batch(b).parameters);
  }
}

double TableGroundIlluminance::directNormalLux(double r, double mu, const std::vector<glm::dvec3>& scale) const {
  double sum = 0.0;
  for (size_t b = 0; b < parameters_.size(); ++b) {
    const shared::AtmosphereParameters& a = parameters_[b];
    const double rr = std::clamp(r, a.bottom_radius + 1.0, a.top_radius - 1.0);
    // Below the horizon the ground hides the light (the light's disc is left out).
    if (shared::rayIntersectsGround(a, rr, mu)) continue;
    const Table& t = transmittance_[b];
    const glm::dvec3 T = t.at(glm::dvec2(shared::transmittanceUvFromRMu(a, rr, mu, glm::ivec2(t.width, t.height))));
    const glm::dvec3 e(a.solar_irradiance[0], a.solar_irradiance[1], a.solar_irradiance[2]);
    const glm::dvec3 rgb = spectra_[b].sunToRgb * (T * e * scale[b]);
    sum += luminanceRec709(rgb.x, rgb.y, rgb.z);
  }
  return sum;
}

double TableGroundIlluminance::lux(double r, double mu, const std::vector<glm::dvec3>& scale) const {
  double sky = 0.0;
  for (size_t b = 0; b < parameters_.size(); ++b) {
    const shared::AtmosphereParameters& a = parameters_[b];
    const double rr = std::clamp(r, a.bottom_radius + 1.0, a.top_radius - 1.0);
    const Table& s = skylight_[b];
    const glm::dvec3 e = s.at(glm::dvec2(shared::irradianceUvFromRMuS(a, rr, mu, glm::ivec2(s.width, s.height))));
    const glm::dvec3 rgb = spectra_[b].skyToRgb * (e * scale[b]);
    sky += luminanceRec709(rgb.x, rgb.y, rgb.z);
  }
  return directNormalLux(r, mu, scale) * std::max(mu, 0.0) + sky;
}

std::vector<glm::dvec3> moonChannelScale(const astro::MoonLight& moon, const std::vector<SpectralBatch>& spectra,
                                         double solarIrradianceScale) {
  std::vector<glm::dvec3> scale;
  for (const SpectralBatch& s : spectra) {
    glm::dvec3 k;
    for (int c = 0; c < 3; ++c)
      k[c] = astro::moonToSolarIrradianceRatio(moon.illuminanceLux, s.wavelengthsNm[c]) / solarIrradianceScale;
    scale.push_back(k);
  }
  return scale;
}

FrameLight chooseFrameLight(double sunGroundLux, double moonGroundLux, const glm::dvec3& sunDirection,
                            const glm::dvec3& moonDirection) {
  FrameLight light;
  light.sunGroundLux = std::max(sunGroundLux, 0.0);
  light.moonGroundLux = std::max(moonGroundLux, 0.0);
  light.moon = light.moonGroundLux > light.sunGroundLux;
  light.direction = light.moon ? moonDirection : sunDirection;
  const double chosen = light.moon ? light.moonGroundLux : light.sunGroundLux;
  const double other = light.moon ? light.sunGroundLux : light.moonGroundLux;
  if (chosen > 0.0 && other > kFrameLightNegligibleRatio * chosen) light.scale = (chosen + other) / chosen;
  char text[200];
  std::snprintf(text, sizeof(text), "%s (ground illuminance: Sun %.3g lx, Moon %.3g lx; the %s carries x%.6g)",
                light.moon ? "the Moon" : "the Sun", light.sunGroundLux, light.moonGroundLux,
                light.moon ? "Moon" : "Sun", light.scale);
  light.reason = text;
  return light;
}

void uploadLightBlocks(gpu::Context& context, const AtmosphereLuts& luts, const std::vector<SpectralBatch>& spectra,
                       const FrameLight& light, std::vector<gpu::Buffer>& blocks) {
  if (light.channelScale.size() != luts.batchCount() || spectra.size() != luts.batchCount())
    throw std::logic_error("uploadLightBlocks: one channel scale and one spectral batch per batch");
  blocks.resize(luts.batchCount());
  for (size_t b = 0; b < luts.batchCount(); ++b) {
    glm::dmat3 scale(0.0);
    for (int c = 0; c < 3; ++c) scale[c][c] = light.channelScale[b][c] * light.scale;
    const AtmosphereBlock block =
        packAtmosphereBlock(luts.batch(b).parameters, spectra[b].skyToRgb * scale, spectra[b].sunToRgb * scale);
    if (!blocks[b])
      blocks[b] = gpu::Buffer(context, sizeof(AtmosphereBlock), gpu::BufferUsage::Uniform, gpu::MemoryLocation::Host,
                              "light atmosphere block");
    blocks[b].upload(&block, sizeof(block));
  }
}

}  // namespace firmament
