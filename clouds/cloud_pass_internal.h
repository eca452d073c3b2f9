#pragma once
// Shared by the cloud pass's files and no one else: clouds/cloud_pass.cpp (the pass, the march), cloud_block.cpp
// (the GPU block), cloud_maps.cpp and the per-frame maps' bakes (cloud_beer_shadow_map.cpp,
// cloud_other_layer_map.cpp, cloud_column_map.cpp, cloud_deep_shadow_map.cpp) and cloud_temporal.cpp (the
// temporal history): which maps a frame bakes and where, the push constants and the block helpers.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "clouds/cloud_settings.h"
#include "gpu/dispatch.h"

namespace firmament::cloud_pass_detail {

constexpr int kMaxLayers = 8;

// The per-frame maps (the other layers' map, clouds/other_layer_map.glsl; the column map,
// clouds/column_map.glsl; the deep shadow map, clouds/deep_shadow_map.glsl). Their log warp's rho0: the distance from
// the map's origin within which texels shrink no further (clouds/log_warp.glsl: a texel's side is (|a| + rho0) ln(1 + E
// / rho0) 2 / N).
constexpr double kMapRho0_m = 1000.0;
// In a sequence the maps are re-baked one in w of their rows per frame (interleaved), so a texel is at
// most w frames old, while the clouds' drift over those frames stays under kMapDrift_m, the sun within
// kMapSunMove_rad of the maps' (a sun line's crossing ~10 km away moves ~1 m) and the camera within
// kMapCameraMove_m of their origin (the extent E is the march's reach plus that); otherwise, and for
// every still, all of them. w is the largest of kMapRowStrides that keeps the drift under the bound
// (10 m/s of wind at 30 frames per second, 0.33 m a frame: 16), and a change of w re-bakes all rows.
// The bound, 8 m, is under a quarter of the smallest texel (34 m at the maps' origin, 256 texels).
constexpr int kMapRowStrides[3] = {16, 8, 4};
constexpr double kMapDrift_m = 8.0;
constexpr double kMapSunMove_rad = 1e-4;
constexpr double kMapCameraMove_m = 1000.0;

// The log warp's scale ln(1 + E / rho0) for a map reaching E = the march's reach + kMapCameraMove_m
// (clouds/log_warp.glsl; once per frame here rather than per lookup).
inline double mapLogWarpScale(const CloudMarchSettings& m) {
  return std::log(1.0 + (m.maxDistance_m + kMapCameraMove_m) / kMapRho0_m);
}

// Whether this frame bakes the column map (clouds/column_map.glsl): the octaves' way from the top and
// the diffusion floor need the vertical optical depths only with more than one octave.
inline bool usesColumnMap(const CloudSettings& settings) {
  return settings.march.columnMap && settings.lighting.octaves > 1;
}
// The ambient's view of the other layers (bake_column_ambient.comp): more than one layer, the ambient on
// as a slab that looks through them.
inline bool usesColumnAmbient(const CloudSettings& settings) {
  const CloudMarchSettings& m = settings.march;
  return usesColumnMap(settings) && settings.layers.size() > 1 && m.ambient && m.ambientSlab &&
         m.ambientThroughOtherLayers;
}

// Whether this frame bakes the other layers' map: light through the other layers, from the map, with
// more than one layer.
inline bool usesOtherLayerMap(const CloudSettings& settings) {
  const CloudMarchSettings& m = settings.march;
  return m.lightThroughOtherLayers && m.otherLayerMap && settings.layers.size() > 1;
}

// Whether this frame bakes the deep shadow map: on, the light march runs to the layer's exit (the map
// holds the way to the top), and it keeps fewer steps than it may take (lightStepsForLength: up to 4
// lightSteps).
inline bool usesDeepShadowMap(const CloudSettings& settings) {
  const CloudMarchSettings& m = settings.march;
  return m.deepShadowMap && m.lightMarchToExit && m.deepShadowNearSteps < 4 * std::max(m.lightSteps, 1);
}

// Whether this frame bakes any of the per-frame maps (they share a placement).
inline bool usesMaps(const CloudSettings& settings) {
  return usesOtherLayerMap(settings) || usesColumnMap(settings) || usesDeepShadowMap(settings);
}

struct Push {
  gpu::TileDispatch tiles;
  int32_t firstBatch;
  int32_t divisor;    // the march's grid is 1/divisor of the image in x and y
  int32_t composite;  // 1: the march composites over the sky; 0: clouds/upsample_clouds or temporal_resolve does
  int32_t noiseShift;
  float pointOffset[2];  // grid pixel p marches image point divisor p + pointOffset
  // A still's sub-frames (CloudMarchSettings::stillSamples): the blue-noise value is moved by
  // jitterShift (mod 1), the march's (L, T) weighted by sampleWeight and written (subFrame 0) or
  // added; the first batch composites over the sky at the last sub-frame.
  float jitterShift;
  float sampleWeight;
  int32_t subFrame;
  int32_t lastSubFrame;
};

struct NeighbourhoodPush {
  gpu::TileDispatch tiles;  // the march's grid
  int32_t offset[2];
  int32_t k;
  int32_t pad;
};

struct ResolvePush {
  gpu::TileDispatch tiles;  // the image
  int32_t gridWidth;
  int32_t gridHeight;
  int32_t k;
  int32_t clampHistory;
  int32_t offset[2];
};

struct UpsamplePush {
  gpu::TileDispatch tiles;  // the image
  int32_t coarseWidth;
  int32_t coarseHeight;
  int32_t divisor;
  int32_t pad;
};

inline void put(float (&out)[4], double x, double y, double z, double w) {
  out[0] = float(x), out[1] = float(y), out[2] = float(z), out[3] = float(w);
}
inline void put(float (&out)[4], const glm::dvec3& v, double w = 0.0) { put(out, v.x, v.y, v.z, w); }

// A unit axis perpendicular to the unit vector d (the second is cross(d, axis)): the maps' placements.
inline glm::dvec3 perpendicularAxis(const glm::dvec3& d) {
  return glm::normalize(std::abs(d.z) < 0.9 ? glm::cross(d, glm::dvec3(0.0, 0.0, 1.0))
                                            : glm::cross(d, glm::dvec3(1.0, 0.0, 0.0)));
}

// The bytes of the cloud block (cloud_block.cpp) and of the temporal block (cloud_temporal.cpp).
size_t cloudBlockBytes();
size_t temporalBlockBytes();

}  // namespace firmament::cloud_pass_detail
