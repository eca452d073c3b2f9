// other_layer_map.glsl: the other layers' optical depth towards the sun, baked once per frame
// (clouds/bake_other_layers.comp) and read by the march (render_clouds.glsl) in place of marching
// every other layer's crossing for every lit sample (docs/clouds.md "The other layers' map").
//
// Why it can be a 2D map: the sun's rays are parallel, so every point on one line along the sun shares
// that line. A point p below layer j's base (r_p < R_b) leaves the sphere R_b once along +sun; from
// there on its radius only grows (past the line's periapsis), so its way to the sun crosses layer j
// exactly once and wholly: from radius R_b to R_t on the line's sunward side. That optical depth
// depends on the line alone. A layer below p is left out: its shadow needs the sun below p's horizon,
// and while the sun still clears the planet (mu_s > -0.035 at 4 km) the marched crossings' 40 km
// (lightMaxLength_m) dropped at most 40 km x 0.035 - (40 km)^2 / 2R ~ 1.3 km below p: only a layer within
// that of p, at the edge of twilight.
//
// Where: a plane through c, the camera of its last full bake, perpendicular to that bake's sun, axes u
// and v (cloud.otherLayerOrigin, AxisU, AxisV, Sun: a sequence re-bakes 1 in 4 to 16 of the rows per frame
// on the same placement, clouds/cloud_maps.cpp). A point's line is where it projects on the plane,
// (a_u, a_v) = ((p - c).u, (p - c).v). Each axis is log-warped to the texel coordinate
// (clouds/log_warp.glsl) out to E, the march's largest distance plus the camera's largest move from c
// (no point the march reaches projects farther). Texels hold up to 4 layers (rgba = layers 4t .. 4t + 3
// in tile t); the tiles are stacked in v.
#ifndef FIRMAMENT_OTHER_LAYER_MAP_GLSL
#define FIRMAMENT_OTHER_LAYER_MAP_GLSL

#include "clouds/log_warp.glsl"

// cloud.otherLayerMap: x = the log warp's scale ln(1 + E / rho0), y = rho0 (m), z = texels per side N, w = tiles (0: no map).

vec2 otherLayerMapPlanePoint(vec2 s) { return logWarpPlanePoint(s, cloud.otherLayerMap.x, cloud.otherLayerMap.y); }
vec2 otherLayerMapTexelCoordinate(vec2 a) { return logWarpTexelCoordinate(a, cloud.otherLayerMap.x, cloud.otherLayerMap.y); }
float otherLayerMapTexelSize(vec2 a) { return logWarpTexelSize(a, cloud.otherLayerMap.x, cloud.otherLayerMap.y, cloud.otherLayerMap.z); }

// Where a line along the sun with periapsis radius r_c reaches radius r on its sunward side: the
// distance from the periapsis, sqrt(r^2 - r_c^2), written as sqrt((r - r_c)(r + r_c)) to keep its
// precision; 0 for a radius the line never comes down to (r <= r_c).
float sunLineDistanceToRadius(float rc, float r) { return sqrt(max((r - rc) * (r + rc), 0.0)); }

// The sunward crossing of the shell [inner, outer] by the line through b along `sun`, b the line's
// periapsis (b.sun = 0, |b| = r_c): the distances along the line from b, (t0, t1); t1 <= t0 when the
// line misses the shell.
vec2 otherLayerMapCrossing(float rc, float inner, float outer) {
  if (!(rc < outer)) return vec2(0.0);
  return vec2(sunLineDistanceToRadius(rc, inner), sunLineDistanceToRadius(rc, outer));
}

// The optical depth towards the sun from p (radius r) through every layer but `own` whose base lies
// above p, read from the map (linear, clamp).
float otherLayerMapOpticalDepth(sampler2D map, int own, vec3 p, float r) {
  vec3 d = p - cloud.otherLayerOrigin.xyz;
  vec2 s = otherLayerMapTexelCoordinate(vec2(dot(d, cloud.otherLayerAxisU.xyz), dot(d, cloud.otherLayerAxisV.xyz)));
  float size = cloud.otherLayerMap.z;
  int tiles = int(cloud.otherLayerMap.w + 0.5);
  // Within the tile: texel centres from 0.5 / N to 1 - 0.5 / N, so no tile reads its neighbour's.
  vec2 uv = clamp(0.5 * s + 0.5, vec2(0.5 / size), vec2(1.0 - 0.5 / size));
  float tau = 0.0;
  for (int t = 0; t < tiles; ++t) {
    vec4 depth = textureLod(map, vec2(uv.x, (float(t) + uv.y) / float(tiles)), 0.0);
    for (int c = 0; c < 4; ++c) {
      int j = 4 * t + c;
      if (j < cloud.image.w && j != own && r < cloud.layers[j].bottomRadius) tau += depth[c];
    }
  }
  return tau;
}

#endif  // FIRMAMENT_OTHER_LAYER_MAP_GLSL
