// The clouds' temporal history (clouds/temporal_neighbourhood.comp, temporal_resolve.comp; decision 0139):
// whether a frame reprojects, which pixel of each block it marches, the resolve and what is kept for the next.
#include "clouds/cloud_pass.h"
#include "clouds/cloud_pass_internal.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace firmament {
using namespace cloud_pass_detail;

namespace {

// std140 mirror of TemporalBlock in shaders/clouds/temporal_resolve.comp.
struct TemporalBlock {
  float cameraPosition[4];
  float cameraForward[4];
  float cameraRight[4];
  float cameraUp[4];
  int32_t image[4];
  float previousPosition[4];
  float previousForward[4];
  float previousRight[4];
  float previousUp[4];
  int32_t previousImage[4];
  float motion[4];
};
static_assert(sizeof(TemporalBlock) == 11 * 16);

// The order in which a k x k block's pixels are marched over k^2 frames: the Bayer matrix's (each
// next pixel far from the ones just marched). kBayer4[n] = (x, y) of the n-th frame's pixel.
constexpr int kBayer2[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
constexpr int kBayer4[16][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};

// Whether a weather map evolved from `before` by no more than the reprojection's clamp absorbs: the
// clouds of a weather scene's 30 fps sequence (the map simulated to each frame's time) change by
// ~1e-4 in coverage per frame, a time-lapse's by far more. The same size and region, the skew within
// 1e-3 m per m (1 m at 1 km), coverage and type within 0.01 and the top within 10 m in every texel
// (precipitation is not read).
bool weatherEvolvedLittle(const std::vector<float>& before, glm::dvec4 regionBefore, const std::vector<float>& now,
                          glm::dvec4 region) {
  if (before.size() != now.size() || regionBefore.x != region.x || regionBefore.y != region.y ||
      std::abs(regionBefore.z - region.z) > 1e-3 || std::abs(regionBefore.w - region.w) > 1e-3)
    return false;
  for (size_t i = 0; i + 3 < now.size(); i += 4)
    if (std::abs(now[i] - before[i]) > 0.01f || std::abs(now[i + 1] - before[i + 1]) > 0.01f ||
        std::abs(now[i + 3] - before[i + 3]) > 10.0f)
      return false;
  return true;
}

}  // namespace

size_t cloud_pass_detail::temporalBlockBytes() { return sizeof(TemporalBlock); }

CloudPass::TemporalPlan CloudPass::planTemporal(const CloudMarchSettings& m, const CloudView& view,
                                                const std::vector<shared::CloudLayer>& layers,
                                                const std::vector<uint8_t>& settingsKey, bool continueSequence) {
  // Temporal reprojection (clouds/temporal_resolve.comp): the march covers every k-th pixel of the
  // image in x and y, one pixel of each k x k block cycling over k^2 frames, when the previous frame
  // can be reprojected: same settings and weather, and the camera outside the layers (flying through a
  // cloud, the parallax inside the volume is not that of one depth per pixel: march everything), at
  // full resolution.
  const int update = m.temporalUpdate;
  if (update != 1 && update != 4 && update != 16)
    throw InputError("clouds: temporal_update " + std::to_string(update) + "; allowed: 1, 4, 16");
  const double cameraRadius = glm::length(view.cameraPosition);
  bool cameraInLayer = false;
  for (const shared::CloudLayer& c : layers) {
    const double margin = 0.05 * (c.top_radius - c.bottom_radius);
    cameraInLayer = cameraInLayer || (cameraRadius > c.bottom_radius - margin && cameraRadius < c.top_radius + margin);
  }
  const glm::dvec3 windOffset = layers.empty() ? glm::dvec3(0.0) : glm::dvec3(layers[0].wind_offset);
  // A reduced-resolution march (divisor > 1) runs every frame instead: it is already the cheap path.
  const int k = m.resolutionDivisor > 1 ? 1 : update == 16 ? 4 : update == 4 ? 2 : 1;
  // The same map, or one that evolved a little (a weather scene's sequence simulates it to each
  // frame's time): what changed the clamp takes out, as it does for the sun's move.
  const bool sameWeather =
      history_.weather == weatherHash_ ||
      weatherEvolvedLittle(history_.weatherTexels, history_.weatherRegion, weatherTexels_, weatherRegion_);
  reprojected_ =
      k > 1 && continueSequence && history_.usable && !cameraInLayer && history_.settings == settingsKey && sameWeather;
  return {k, windOffset, sameWeather};
}

void CloudPass::blockPixel(int k, int offset[2]) const {
  const int n = int(temporalFrame_ % uint32_t(k * k));
  offset[0] = k == 4 ? kBayer4[n][0] : kBayer2[n][0];
  offset[1] = k == 4 ? kBayer4[n][1] : kBayer2[n][1];
}

void CloudPass::recordTemporalResolve(const CloudView& view, const CloudMarchSettings& m, const TemporalPlan& plan,
                                      uint32_t coarseWidth, uint32_t coarseHeight, const gpu::TileDispatch& marchTiles,
                                      const gpu::TileDispatch& tiles, const int offset[2], gpu::Buffer& cloudFrame,
                                      const gpu::Buffer& historyFrame, gpu::Buffer& skyFrame,
                                      gpu::CommandList& commands) {
  TemporalBlock t{};
  put(t.cameraPosition, view.cameraPosition);
  put(t.cameraForward, view.camera.forward, view.camera.fov);
  put(t.cameraRight, view.camera.right, view.camera.yaw);
  put(t.cameraUp, view.camera.up);
  t.image[0] = view.camera.width, t.image[1] = view.camera.height, t.image[2] = view.camera.projection;
  const CloudView& p = history_.view;
  put(t.previousPosition, p.cameraPosition);
  put(t.previousForward, p.camera.forward, p.camera.fov);
  put(t.previousRight, p.camera.right, p.camera.yaw);
  put(t.previousUp, p.camera.up);
  t.previousImage[0] = p.camera.width, t.previousImage[1] = p.camera.height, t.previousImage[2] = p.camera.projection;
  // The noise is read at p + wind offset: a feature at P now was at P + (offset now - offset then).
  // The clamp everywhere in proportion to the sun's move, fully from 0.25 degrees per frame (a
  // time-lapse; the day's course moves it ~1e-4 degrees per frame at 30 frames per second).
  const double sunMove =
      std::acos(std::clamp(glm::dot(glm::normalize(view.sunDirection), glm::normalize(p.sunDirection)), -1.0, 1.0));
  put(t.motion, plan.windOffset - history_.windOffset, std::clamp(sunMove / (0.25 * shared::kPi / 180.0), 0.0, 1.0));
  temporalBlock_.upload(&t, sizeof(t));
  // The fresh neighbourhoods once per grid pixel, then the image (both timed as the resolve).
  const VkDeviceSize records = VkDeviceSize(coarseWidth) * coarseHeight * 3 * 4 * sizeof(float);
  if (!neighbourhoodRecords_ || neighbourhoodRecords_.size() < records)
    neighbourhoodRecords_ =
        gpu::Buffer(context_, records, gpu::BufferUsage::Storage, gpu::MemoryLocation::Device, "cloud neighbourhoods");
  // Bindings 3 and 4 are unused by the neighbourhood pass (its layout mirrors the resolve's numbering).
  commands.bind(neighbourhood_, {coarseFrame_, depth_, neighbourhoodRecords_, historyFrame, skyFrame, temporalBlock_});
  NeighbourhoodPush neighbourhoodPush{marchTiles, {offset[0], offset[1]}, plan.k, 0};
  commands.pushConstants(neighbourhoodPush);
  commands.dispatchTiles(marchTiles, "clouds/temporal_resolve");
  commands.barrier();
  commands.bind(resolve_,
                {coarseFrame_, depth_, historyFrame, cloudFrame, skyFrame, temporalBlock_, neighbourhoodRecords_});
  ResolvePush push{tiles,  int32_t(coarseWidth),    int32_t(coarseHeight),
                   plan.k, m.temporalClamp ? 1 : 0, {offset[0], offset[1]}};
  commands.pushConstants(push);
  commands.dispatchTiles(tiles, "clouds/temporal_resolve");
  ++temporalFrame_;
}

void CloudPass::rememberHistory(std::vector<uint8_t> settingsKey, const CloudView& view, const TemporalPlan& plan) {
  history_.usable = plan.k > 1;
  history_.settings = std::move(settingsKey);
  if (history_.weather != weatherHash_) history_.weatherTexels = weatherTexels_;  // copied only when it changed
  history_.weather = weatherHash_;
  history_.weatherRegion = weatherRegion_;
  history_.view = view;
  history_.windOffset = plan.windOffset;
}

}  // namespace firmament
