// log_warp.glsl: the texel placement both per-frame maps use (clouds/other_layer_map.glsl,
// clouds/column_map.glsl): a plane coordinate a (m, per axis) maps to the texel coordinate s in [-1, 1] by
//   s = sign(a) ln(1 + |a| / rho0) / L,   L = ln(1 + E / rho0) (the scale, computed on the host),
// so a texel's side, |da/ds| 2 / N = (|a| + rho0) L 2 / N, grows in proportion to the distance from
// the map's origin, as a pixel's footprint does, out to E.
#ifndef FIRMAMENT_LOG_WARP_GLSL
#define FIRMAMENT_LOG_WARP_GLSL

// The plane coordinate a (m) of texel coordinate s.
vec2 logWarpPlanePoint(vec2 s, float scale, float rho0) { return sign(s) * rho0 * (exp(abs(s) * scale) - 1.0); }

// The texel coordinate s (clamped to [-1, 1]) of plane coordinate a (m).
vec2 logWarpTexelCoordinate(vec2 a, float scale, float rho0) { return clamp(sign(a) * log(1.0 + abs(a) / rho0) / scale, -1.0, 1.0); }

// The side (m, the larger axis) of the texel at plane coordinate a, N texels per side.
float logWarpTexelSize(vec2 a, float scale, float rho0, float N) { return (max(abs(a.x), abs(a.y)) + rho0) * scale * 2.0 / N; }

#endif  // FIRMAMENT_LOG_WARP_GLSL
