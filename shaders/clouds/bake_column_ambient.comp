#version 450
#extension GL_GOOGLE_include_directive : require
// Bakes the ambient's view of the other layers into the column map (clouds/column_map.glsl): per
// column and layer j, the similarity-scaled optical depth of the other layers above j (slice
// columnMapAmbientSlice(j)) and below it (the next slice), read by the march's ambient slab
// (common/cloud_lighting.glsl cloudAmbientGroundWeight; CloudMarchSettings::ambientThroughOtherLayers).
// Runs after bake_columns (it reads the layers' whole columns, level 0, at other texels).
//
// Why: in a plane-parallel column the clear air between two layers changes nothing for diffuse light,
// only the optical depth counts, so a deck above dims the sky a layer below sees and a layer below
// turns the sky's light back up. But a broken layer a distance D away is seen through its gaps: the
// mean radiance J weighs every direction of the hemisphere alike, and direction theta crosses the
// other layer at a horizontal offset D tan(theta). So each other layer's diffuse transmission
//   T = (4/3) / (4/3 + tau')
// (cloudDiffuseSlabTransmission: a conservative slab's under diffuse light, Eddington with Marshak's
// boundaries; tau' = (1 - g) tau of the column there, similarity-scaled) is averaged over 9 columns, three in each third of the
// hemisphere's solid angle (cos(theta) 5/6, 1/2, 1/6: tan(theta) 0.663, 1.732, 5.916), and given back
// as the depth of a uniform layer with that mean, tau' = (1/T - 1) 4/3 (cloudDiffuseSlabDepth). A uniform layer comes back
// unchanged. D is from the middle of layer j to the middle of the other (at least half the other's
// thickness). Marching these 9 lookups per lit sample instead cost 18 % of two_layers' still.
#include "clouds/cloud_sampling.glsl"
#include "clouds/column_map.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 13, r32f) uniform image3D columnImage;

// The whole column of layer i at plane point a (nearest texel, clamped to the map).
float wholeColumn(vec2 a, int i, int K) {
  ivec2 texel = ivec2(floor(columnMapPlaneCoordinate(a) * cloud.columnMap.z));
  return imageLoad(columnImage, ivec3(texel, i * (K + 1))).r;
}

void main() {
  int size = int(cloud.columnMap.z + 0.5);
  int K = int(cloud.columnMap.w + 0.5);
  int j = int(gl_GlobalInvocationID.z);
  int stride = max(int(cloud.columnAxisU.w + 0.5), 1);  // the rows bake_columns baked this frame
  ivec2 texel = ivec2(gl_GlobalInvocationID.x, int(gl_GlobalInvocationID.y) * stride + int(cloud.columnOrigin.w + 0.5));
  if (texel.x >= size || texel.y >= size || j >= cloud.image.w) return;
  vec2 a = columnMapPlanePoint((vec2(texel) + 0.5) / float(size) * 2.0 - 1.0);
  // The similarity scale 1 - g of the light paths' phase (δ-scaled: the scaled medium's, times its
  // sigma_t' / sigma_t), as the march takes it.
  float similarity = cloudLightTransportScale() * (1.0 - cloudLightPhaseMeanCosine());
  CloudLayer own = layerAt(j);
  float middle = 0.5 * (own.bottom_radius + own.top_radius);
  const float kTan[3] = float[3](0.663, 1.732, 5.916);
  vec2 depths = vec2(0.0);
  for (int i = 0; i < cloud.image.w; ++i) {
    if (i == j) continue;
    CloudLayer other = layerAt(i);
    float otherMiddle = 0.5 * (other.bottom_radius + other.top_radius);
    float distance = max(abs(otherMiddle - middle), 0.5 * (other.top_radius - other.bottom_radius));
    float meanTransmission = 0.0;
    for (int band = 0; band < 3; ++band)
      for (int k = 0; k < 3; ++k) {
        float angle = 2.0943951 * float(k) + 1.0471976 * float(band);  // 120 deg apart, each band turned 60 deg
        vec2 offset = distance * kTan[band] * vec2(cos(angle), sin(angle));
        meanTransmission += (1.0 / 9.0) * cloudDiffuseSlabTransmission(similarity * wholeColumn(a + offset, i, K));
      }
    float depth = cloudDiffuseSlabDepth(meanTransmission);
    if (otherMiddle > middle)
      depths.x += depth;
    else
      depths.y += depth;
  }
  int slice = columnMapAmbientSlice(j);
  imageStore(columnImage, ivec3(texel, slice), vec4(depths.x));
  imageStore(columnImage, ivec3(texel, slice + 1), vec4(depths.y));
}
