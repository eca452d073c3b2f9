// deep_shadow_map.glsl: each layer's own optical depth towards the sun from any point, baked once per
// frame (clouds/bake_deep_shadow.comp) and read by the light march (render_clouds.glsl) in place of its
// far samples: the march keeps its first `near` steps (the shadow's detail next to the sample) and takes
// the rest of the way to the layer top from the map in one lookup (docs/clouds.md "The deep shadow map").
// Lokovic and Veach 2000's deep shadow map, here of optical depth, per layer.
//
// Why it can be a map: the sun's rays are parallel, so every point on one line along the sun shares the
// rest of that line. Past the line's periapsis b (b.sun = 0, |b| = r_c) the radius grows along +sun, so
// a point p with p.sun > 0 lies on that sunward side, and its way to the sun through its own layer
// leaves through the top at radius R_t. On that side the radius r names the point: it lies t(r) =
// sqrt(r^2 - r_c^2) from b. Per layer and line the map holds the optical depth from K + 1 levels
// r_k = R_b + k H / K (k = 0 .. K) up to the top,
//   T(k) = sum over the level segments above r_k of sigma(midpoint) (t(r_{k+1}) - t(r_k)),   T(K) = 0,
// so a point at height fraction z on the line reads T(z), linear between the levels (a point below the
// base reads the whole crossing T(0), one above the top 0). A point with
// p.sun <= 0 (the sun at or below its horizon: its ray first descends) is marched all the way.
//
// Where: the other layers' map's plane, axes and sun (clouds/other_layer_map.glsl): a point's line is
// its projection on the plane, log-warped (clouds/log_warp.glsl). Slices: layer j's levels are slices
// j (K + 1) .. j (K + 1) + K of a 3D map (as the column map's).
#ifndef FIRMAMENT_DEEP_SHADOW_MAP_GLSL
#define FIRMAMENT_DEEP_SHADOW_MAP_GLSL

#include "clouds/other_layer_map.glsl"

// cloud.deepShadowMap: x = texels per side N, y = levels K, z = the light march's near steps, w = 1 when baked.

// Where q's line meets the map's plane: q projected on it, (a_u, a_v) (m).
vec2 deepShadowMapPlanePoint(vec3 q) {
  vec3 d = q - cloud.otherLayerOrigin.xyz;
  return vec2(dot(d, cloud.otherLayerAxisU.xyz), dot(d, cloud.otherLayerAxisV.xyz));
}

// That line's place in the map, in texels (centres at i + 0.5), clamped to the texel centres: the plane
// point a log-warped. The lookups below take a and f, so that one lit sample's two lookups (its way to
// the top and its line's whole crossing, for the reflected light) project and warp once.
vec2 deepShadowMapTexel(vec2 a) {
  float size = cloud.deepShadowMap.x;
  return clamp((0.5 * otherLayerMapTexelCoordinate(a) + 0.5) * size - 0.5, vec2(0.0), vec2(size - 1.0));
}

// The optical depth from q (in `layer`, index j, q.sun > 0, its plane point a and texel f) along the sun
// up to the layer top, read from the map. Between lines the interpolation is bilinear in the plane,
// each of the four nearest lines read at the point it shares q's distance along the sun with,
// q' = q + (a' - a) in the plane (its level from |q'|, linear between levels): reading them all at q's
// own level instead sheared the interpolation along the sun when the sun is low (neighbouring lines a
// texel apart in v pass q's height ~1 km apart along a 10-degree sun ray), 3-6 % from the march against
// 0.2-1 % this way.
float deepShadowMapOpticalDepth(sampler3D map, int j, CloudLayer layer, vec3 q, vec2 a, vec2 f) {
  vec3 u = cloud.otherLayerAxisU.xyz, v = cloud.otherLayerAxisV.xyz;
  float size = cloud.deepShadowMap.x;
  vec2 i0 = min(floor(f), vec2(size - 2.0));
  vec2 w = f - i0;
  float K = cloud.deepShadowMap.y;
  float slices = float(cloud.image.w) * (K + 1.0);
  float base = float(j) * (K + 1.0);
  float thickness = max(layer.top_radius - layer.bottom_radius, 1.0);
  float tau = 0.0;
  for (int c = 0; c < 4; ++c) {
    vec2 corner = i0 + vec2(c & 1, c >> 1);
    vec2 a1 = otherLayerMapPlanePoint((corner + 0.5) / size * 2.0 - 1.0);
    vec3 q1 = q + (a1.x - a.x) * u + (a1.y - a.y) * v;
    float z = clamp((length(q1) - layer.bottom_radius) / thickness, 0.0, 1.0);
    float depth = textureLod(map, vec3((corner + 0.5) / size, (base + z * K + 0.5) / slices), 0.0).r;
    vec2 weight = mix(1.0 - w, w, vec2(c & 1, c >> 1));
    tau += weight.x * weight.y * depth;
  }
  return tau;
}

// The whole sunward crossing of the line at texel f through layer j, T(0): the level-0 slice, bilinear
// between lines (one level, so the four lines need no shift along the sun).
float deepShadowMapCrossing(sampler3D map, int j, vec2 f) {
  float size = cloud.deepShadowMap.x;
  float slices = float(cloud.image.w) * (cloud.deepShadowMap.y + 1.0);
  return textureLod(map, vec3((f + 0.5) / size, (float(j) * (cloud.deepShadowMap.y + 1.0) + 0.5) / slices), 0.0).r;
}

#endif  // FIRMAMENT_DEEP_SHADOW_MAP_GLSL
