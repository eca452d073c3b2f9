// column_map.glsl: each layer's optical depth straight up and straight down from any point, baked once
// per frame (clouds/bake_columns.comp) and read by the march (render_clouds.glsl) in place of the two
// vertical marches each lit sample made: the way down from the layer top for the octaves i >= 1 and
// the diffusion floor (docs/clouds.md "The column map").
//
// Why it can be a map: "straight up" from p is the radial line through p, so all points of one column
// (one direction from the planet centre) share it. Per layer and column the map holds the optical depth
// from K + 1 levels r_k = R_b + k H / K (k = 0 .. K) up to the top,
//   T(k) = sum over the segments above r_k of sigma(midpoint) H / K,   T(K) = 0,
// so a point at height fraction z reads T(z), linear between the levels, for its way up and T(0) - T(z)
// for its way down to the base.
//
// Where: the columns' directions q, placed by the gnomonic projection at the camera's ground point
// (unit normal c, axes u and v, planet radius R): a = R (q.u, q.v) / (q.c), each axis log-warped to the
// texel coordinate as the other layers' map is (clouds/log_warp.glsl): a texel's side grows like
// (|a| + rho0) out to E. Slices: layer j's levels are slices j (K + 1) .. j (K + 1) + K of a 3D map.
#ifndef FIRMAMENT_COLUMN_MAP_GLSL
#define FIRMAMENT_COLUMN_MAP_GLSL

#include "clouds/log_warp.glsl"

// cloud.columnMap: x = the log warp's scale ln(1 + E / rho0), y = rho0 (m), z = texels per side N, w = levels K (0: no map).
// cloud.columnOrigin.xyz = c, cloud.columnAxisU.xyz = u, cloud.columnAxisV.xyz = v, cloud.columnAxisV.w = R.

// The map's slices: K + 1 levels per layer, then two per layer for the ambient (the other layers'
// depths above and below, bake_column_ambient.comp).
float columnMapSlices() { return float(cloud.image.w) * (cloud.columnMap.w + 1.0) + 2.0 * float(cloud.image.w); }
int columnMapAmbientSlice(int j) { return cloud.image.w * (int(cloud.columnMap.w + 0.5) + 1) + 2 * j; }

vec2 columnMapPlanePoint(vec2 s) { return logWarpPlanePoint(s, cloud.columnMap.x, cloud.columnMap.y); }
float columnMapTexelSize(vec2 a) { return logWarpTexelSize(a, cloud.columnMap.x, cloud.columnMap.y, cloud.columnMap.z); }

// The unit direction of the column at plane point a.
vec3 columnMapDirection(vec2 a) {
  float R = cloud.columnAxisV.w;
  return normalize(cloud.columnOrigin.xyz + (a.x / R) * cloud.columnAxisU.xyz + (a.y / R) * cloud.columnAxisV.xyz);
}

// The map coordinate of plane point a: log-warped, clamped to the outermost texel centres.
vec2 columnMapPlaneCoordinate(vec2 a) {
  float size = cloud.columnMap.z;
  vec2 s = logWarpTexelCoordinate(a, cloud.columnMap.x, cloud.columnMap.y);
  return clamp(0.5 * s + 0.5, vec2(0.5 / size), vec2(1.0 - 0.5 / size));
}

// The map coordinate of p's column (p at radius r): its plane point by the gnomonic projection.
vec2 columnMapCoordinate(vec3 p, float r) {
  vec3 q = p / r;
  float R = cloud.columnAxisV.w;
  float g = max(dot(q, cloud.columnOrigin.xyz), 1e-3);
  return columnMapPlaneCoordinate(R * vec2(dot(q, cloud.columnAxisU.xyz), dot(q, cloud.columnAxisV.xyz)) / g);
}

// The optical depths from p (radius r, in `layer`, index j) straight up to the top (x) and straight down
// to the base (y), read from the map (linear, clamp).
vec2 columnMapOpticalDepths(sampler3D map, int j, CloudLayer layer, vec3 p, float r) {
  vec2 uv = columnMapCoordinate(p, r);
  float K = cloud.columnMap.w;
  float slices = columnMapSlices();
  float z = clamp((r - layer.bottom_radius) / max(layer.top_radius - layer.bottom_radius, 1.0), 0.0, 1.0);
  float base = float(j) * (K + 1.0);
  float above = textureLod(map, vec3(uv, (base + z * K + 0.5) / slices), 0.0).r;
  float total = textureLod(map, vec3(uv, (base + 0.5) / slices), 0.0).r;
  return vec2(above, max(total - above, 0.0));
}

// The other layers as the ambient's slab sees them (cloudAmbientGroundWeight): their similarity-scaled
// optical depths above (x) and below (y) layer j at p's column, baked per column and layer by
// bake_column_ambient.comp (why and how there), read linear.
vec2 columnMapOtherLayersOpticalDepths(sampler3D map, int j, vec3 p, float r) {
  vec2 uv = columnMapCoordinate(p, r);
  float slices = columnMapSlices();
  float slice = float(columnMapAmbientSlice(j));
  return vec2(textureLod(map, vec3(uv, (slice + 0.5) / slices), 0.0).r, textureLod(map, vec3(uv, (slice + 1.5) / slices), 0.0).r);
}

#endif  // FIRMAMENT_COLUMN_MAP_GLSL
