// cloud_density.glsl: the cloud medium, written once for the GPU march (GLSL, float) and the CPU
// path tracer (C++, double); see compat.glsl for the rules and docs/clouds.md for the model.
//
// A layer is a spherical shell bottom_radius <= r <= top_radius around the planet centre. At a point
// p (planet-centred, m) with height fraction p_h = (r - r_bottom) / (r_top - r_bottom) the extinction
// is
//     sigma_t(p) = extinction * d(p),   d in [0, density_scale],
// with `extinction` in m^-1 (the type's value at density 1 times the scene's scale) and d built from
// the noise textures as in Häggström 2018 ("Real-time rendering of volumetric clouds", section 3.1),
// which follows Schneider 2015/2017 (the Nubis system):
//   eq. 11  SN_sample = R(sn_r, (0.625 sn_g + 0.25 sn_b + 0.125 sn_a) - 1, 1, 0, 1)
//   eq. 15  SN_nd     = SAT(R(SN_sample * SA, 1 - g_c WM_c, 1, 0, 1))   (coverage as a threshold)
//   eq. 13  DN_fbm    = 0.625 dn_r + 0.25 dn_g + 0.125 dn_b
//   eq. 14  DN_mod    = s_d e^(-0.75 g_c) L_i(DN_fbm, 1 - DN_fbm, SAT(5 p_h))   (s_d = 0.35 there)
//   eq. 16  d         = SAT(R(SN_nd, DN_mod, 1, 0, 1)) * DA
// R is the remap below, SAT a clamp to [0, 1], L_i a linear interpolation, g_c the layer's coverage,
// WM_c the weather map's coverage, SA the type's shape-altering height profile and DA its
// density-altering height profile (with the cumulonimbus anvil of eqs. 17 and 18).
// The noise values themselves are texture lookups (GPU: shaders/clouds/cloud_sampling.glsl; CPU:
// clouds/noise_volume.h on the read-back textures); this header maps positions to texture coordinates
// and noise values to density, so both sides evaluate the same medium.
//
// Bound used by the empty-space skipping and the path tracer's majorant: with x <= 1 and m in [0, 1),
// R(x, m, 1, 0, 1) = (x - m) / (1 - m) <= x, so d <= SN_nd * DA <= density_scale. In particular
// SN_nd = 0 (the cheap shape-only density) implies d = 0 exactly.
#ifndef FIRMAMENT_CLOUD_DENSITY_GLSL
#define FIRMAMENT_CLOUD_DENSITY_GLSL

#include "common/compat.glsl"
#include "common/geometry.glsl"

SHARED_BEGIN

const int kCloudStratus = 0;
const int kCloudStratocumulus = 1;
const int kCloudCumulus = 2;
const int kCloudCumulonimbus = 3;
const int kCloudCirrus = 4;

struct CloudLayer {
  Real bottom_radius;    // m from the planet centre
  Real top_radius;       // m
  Real coverage;         // g_c in [0, 1]
  Real extinction;       // m^-1 at density 1 (type value x the scene's extinction scale)
  Real density_scale;    // g_d >= 0 (multiplies d)
  Real anvil;            // a_a in [0, 1] (cumulonimbus only)
  Real shape_period;     // m: one period of the shape texture
  Real detail_period;    // m: one period of the detail texture
  Real detail_strength;  // s_d: the largest erosion by the detail noise (Häggström 0.35)
  Real curl_period;      // m: one period of the curl texture
  Real curl_strength;    // m: displacement of the detail lookup by the curl field at the base
  vec3 wind_offset;      // m: wind x time, added to positions before the lookups
  vec2 skew;             // m of horizontal shift per m of height (wind shear: towers lean downwind)
  int kind;              // kCloud*
  // Set per map column by cloudColumnLayer (common/cloud_weather.glsl) from the weather map's type;
  // 0 for the layer itself: the profiles are mix(kind's, stratiform_kind's, stratiform).
  Real stratiform;       // weight in [0, 1] of the stratiform profile
  int stratiform_kind;   // kCloudStratus or kCloudStratocumulus
};

SHARED_INLINE Real cloudSaturate(Real x) { return clamp(x, 0.0, 1.0); }

// R(x, a, b, c, d) = c + (x - a) (d - c) / (b - a) (Häggström eq. 1), for a != b.
SHARED_INLINE Real cloudRemap(Real x, Real a, Real b, Real c, Real d) {
  return c + (x - a) * (d - c) / (b - a);
}

SHARED_INLINE Real cloudHeightFraction(CloudLayer layer, Real r) {
  return (r - layer.bottom_radius) / (layer.top_radius - layer.bottom_radius);
}

// Shape-altering height profile SA(p_h) in [0, 1] per type: where in the shell a type can be.
//   cumulus:       Häggström eqs. 5-7 with w_h = 1: SAT(R(p_h, 0, 0.07, 0, 1)) SAT(R(p_h, 0.2, 1, 1, 0)),
//                  rounded at the base, tapering towards the top;
//   cumulonimbus:  the same, raised to the anvil exponent of eq. 17,
//                  SA^SAT(R(p_h, 0.65, 0.95, 1, 1 - a_a g_c)): the top widens as a_a g_c -> 1;
//   stratus:       a flat slab filling the shell with soft 10 % edges;
//   stratocumulus: a slab with a 10 % base ramp and a top fading over the upper 40 % (lumpy tops);
//   cirrus:        a thin sheet with soft edges over the middle of its shell.
// The slab and sheet gradients follow Schneider 2015's per-type height gradients.
//
// Every type's profile is a base ramp over [0, rampTop] times a fade over [fadeFrom, 1]; the types differ
// only in the two bounds, so they are picked as numbers rather than by branches (lavapipe runs every
// branch of a shader, whichever its lanes take).
SHARED_INLINE Real cloudShapeRamps(Real ph, Real rampTop, Real fadeFrom) {
  return cloudSaturate(cloudRemap(ph, 0.0, rampTop, 0.0, 1.0)) * cloudSaturate(cloudRemap(ph, fadeFrom, 1.0, 1.0, 0.0));
}
// The two bounds per type (cumulonimbus: cumulus's, before its anvil exponent).
SHARED_INLINE Real cloudShapeRampTop(int kind) {
  return kind == kCloudCirrus ? 0.3 : (kind == kCloudStratus || kind == kCloudStratocumulus) ? 0.1 : 0.07;
}
SHARED_INLINE Real cloudShapeFadeFrom(int kind) {
  return kind == kCloudStratus ? 0.9 : kind == kCloudStratocumulus ? 0.6 : kind == kCloudCirrus ? 0.7 : 0.2;
}
// A profile without the cumulonimbus anvil: the stratiform blend's (stratus or stratocumulus), whose
// kind never has one.
SHARED_INLINE Real cloudSlabShapeProfile(int kind, Real ph) {
  return cloudShapeRamps(ph, cloudShapeRampTop(kind), cloudShapeFadeFrom(kind));
}
SHARED_INLINE Real cloudShapeProfile(int kind, Real ph, Real coverage, Real anvil) {
  Real sa = cloudSlabShapeProfile(kind, ph);
  if (kind == kCloudCumulonimbus) {
    Real exponent = cloudSaturate(cloudRemap(ph, 0.65, 0.95, 1.0, 1.0 - anvil * coverage));  // eq. 17
    sa = sa > 0.0 ? pow(sa, exponent) : 0.0;
  }
  return sa;
}

// Density-altering height profile DA(p_h) in [0, 1] per type (times density_scale elsewhere).
//   cumulus, cumulonimbus: Häggström eqs. 8-10 without the factor 2 w_d (no weather density yet):
//       DR_b DR_t = p_h SAT(R(p_h, 0, 0.15, 0, 1)) * SAT(R(p_h, 0.9, 1, 1, 0)),
//     wispy at the base, dense towards the top; the cumulonimbus anvil is thinned by eq. 18,
//       DA_anvil = DA L_i(1, SAT(R(sqrt(p_h), 0.4, 0.95, 1, 0.2)), a_a);
//   stratus, stratocumulus, cirrus: nearly uniform (0.6 at the base rising to 1 over 20 %), soft top.
// Every type: a base part times the soft top SAT(R(p_h, 0.9, 1, 1, 0)), chosen by select (as above).
SHARED_INLINE Real cloudDensityTopFade(Real ph) { return cloudSaturate(cloudRemap(ph, 0.9, 1.0, 1.0, 0.0)); }
SHARED_INLINE Real cloudSlabDensityBase(Real ph) { return cloudSaturate(cloudRemap(ph, 0.0, 0.2, 0.6, 1.0)); }
// The stratiform (and cirrus) profile alone: the stratiform blend's.
SHARED_INLINE Real cloudSlabDensityProfile(Real ph) { return cloudSlabDensityBase(ph) * cloudDensityTopFade(ph); }
SHARED_INLINE Real cloudDensityProfile(int kind, Real ph, Real anvil) {
  bool convective = kind == kCloudCumulus || kind == kCloudCumulonimbus;
  Real base = convective ? ph * cloudSaturate(cloudRemap(ph, 0.0, 0.15, 0.0, 1.0)) : cloudSlabDensityBase(ph);
  Real da = base * cloudDensityTopFade(ph);
  if (kind == kCloudCumulonimbus) da *= mix(1.0, cloudSaturate(cloudRemap(sqrt(max(ph, 0.0)), 0.4, 0.95, 1.0, 0.2)), anvil);  // eq. 18
  return da;
}

// The column's profiles: the kind's, blended towards the stratiform kind's by the weather map's type
// (cloudColumnLayer). Without a blend exactly the kind's.
SHARED_INLINE Real cloudLayerShapeProfile(CloudLayer layer, Real ph) {
  Real sa = layer.stratiform < 1.0 ? cloudShapeProfile(layer.kind, ph, layer.coverage, layer.anvil) : 0.0;
  if (layer.stratiform <= 0.0) return sa;
  return mix(sa, cloudSlabShapeProfile(layer.stratiform_kind, ph), layer.stratiform);
}
SHARED_INLINE Real cloudLayerDensityProfile(CloudLayer layer, Real ph) {
  Real da = layer.stratiform < 1.0 ? cloudDensityProfile(layer.kind, ph, layer.anvil) : 0.0;
  if (layer.stratiform <= 0.0) return da;
  return mix(da, cloudSlabDensityProfile(ph), layer.stratiform);
}

// Position (planet-centred, m) -> shape texture coordinate (in periods; the sampler repeats). The
// origin is the point of the layer's bottom sphere on the +z axis (below the camera), so coordinates
// stay small near the camera (float keeps ~1 cm at 100 km). Wind moves the field; the skew shifts it
// downwind with height.
SHARED_INLINE vec3 cloudLocalPosition(CloudLayer layer, vec3 p) {
  Real h = length(p) - layer.bottom_radius;
  return vec3(p.x + layer.wind_offset.x + layer.skew.x * h, p.y + layer.wind_offset.y + layer.skew.y * h,
              p.z - layer.bottom_radius + layer.wind_offset.z);
}

SHARED_INLINE vec3 cloudShapeCoordinate(CloudLayer layer, vec3 local) { return local / layer.shape_period; }

SHARED_INLINE vec2 cloudCurlCoordinate(CloudLayer layer, vec3 local) {
  return vec2(local.x / layer.curl_period, local.y / layer.curl_period);
}

// The detail lookup is displaced horizontally by the curl field (decoded from [0, 1] to [-1, 1]),
// most at the base, where Schneider 2017 uses it to make wispy, turbulent bottoms.
SHARED_INLINE vec3 cloudDetailCoordinate(CloudLayer layer, vec3 local, vec2 curl01, Real ph) {
  Real displacement = layer.curl_strength * (1.0 - cloudSaturate(ph));
  vec3 q = vec3(local.x + displacement * (2.0 * curl01.x - 1.0), local.y + displacement * (2.0 * curl01.y - 1.0), local.z);
  return q / layer.detail_period;
}

// SN_nd (eqs. 11 and 15): the shape-only density in [0, 1], before the detail erosion and DA; 0 outside
// the shell. weatherCoverage = WM_c in [0, 1] (1 where no weather map drives the layer).
//
// cloudShapeSignedDensity is eq. 15 before its clamp: <= 0 outside the cloud, and how far below 0 says
// how far the point is from the shape's edge (-1 outside the shell or without coverage). The march's
// empty-space test uses it with a margin (docs/clouds.md, "Empty-space skipping").
SHARED_INLINE Real cloudShapeSignedDensity(CloudLayer layer, Real ph, vec4 shape, Real weatherCoverage) {
  if (ph <= 0.0 || ph >= 1.0) return -1.0;
  Real coverage = cloudSaturate(layer.coverage * weatherCoverage);
  if (coverage <= 0.0) return -1.0;  // R(x, 1, 1, 0, 1) is 0/0: no coverage, no cloud
  Real fbm = 0.625 * shape.y + 0.25 * shape.z + 0.125 * shape.w;
  Real shapeSample = cloudSaturate(cloudRemap(shape.x, fbm - 1.0, 1.0, 0.0, 1.0));                   // eq. 11
  Real sa = cloudLayerShapeProfile(layer, ph);
  // eq. 15 with the threshold 1 - c: R(x, 1 - c, 1, 0, 1) = (x - 1 + c) / c.
  return min((shapeSample * sa - 1.0 + coverage) / coverage, 1.0);
}
SHARED_INLINE Real cloudShapeDensity(CloudLayer layer, Real ph, vec4 shape, Real weatherCoverage) {
  return max(cloudShapeSignedDensity(layer, ph, shape, weatherCoverage), 0.0);
}

// d (eqs. 13, 14, 16): the final density, 0 <= d <= shapeDensity * density_scale.
SHARED_INLINE Real cloudDensity(CloudLayer layer, Real ph, Real shapeDensity, vec4 detail) {
  if (shapeDensity <= 0.0) return 0.0;
  Real fbm = 0.625 * detail.x + 0.25 * detail.y + 0.125 * detail.z;                                // eq. 13
  Real erosion = layer.detail_strength * exp(-layer.coverage * 0.75) * mix(fbm, 1.0 - fbm, cloudSaturate(ph * 5.0));  // eq. 14
  erosion = clamp(erosion, 0.0, 0.99);
  Real eroded = cloudSaturate((shapeDensity - erosion) / (1.0 - erosion));                        // eq. 16
  return eroded * cloudLayerDensityProfile(layer, ph) * layer.density_scale;
}

// The parts of the ray (r, mu) inside the shell inner <= radius <= outer, clipped to [0, tMax]: the ray
// is inside where it is within the outer sphere (tOuterNear <= t <= tOuterFar) and not within the
// inner one (not tInnerNear < t < tInnerFar), which holds for a camera below, inside or above the
// shell. At most two stretches: `first` before the inner sphere, `second` after it (from above or
// inside, looking down past the inner sphere's top). Each is (start, end), empty when end <= start.
// Tangent rays give zero-length stretches (the discriminant is 0), never NaN.
SHARED_INLINE void cloudShellSegments(Real r, Real mu, Real inner, Real outer, Real tMax, OUT(vec2) first, OUT(vec2) second) {
  Real oNear;
  Real oFar;
  Real iNear;
  Real iFar;
  first = vec2(0.0, 0.0);
  second = vec2(0.0, 0.0);
  if (!raySphereRoots(r, mu, outer, oNear, oFar)) return;
  bool hitsInner = raySphereRoots(r, mu, inner, iNear, iFar);
  Real aEnd = hitsInner ? min(iNear, oFar) : oFar;
  first = vec2(clamp(oNear, 0.0, tMax), clamp(aEnd, 0.0, tMax));
  if (hitsInner) second = vec2(clamp(max(iFar, oNear), 0.0, tMax), clamp(oFar, 0.0, tMax));
}

// The largest extinction anywhere in the layer (m^-1): a majorant for delta tracking.
SHARED_INLINE Real cloudMajorant(CloudLayer layer) { return layer.extinction * layer.density_scale; }

SHARED_END

#endif  // FIRMAMENT_CLOUD_DENSITY_GLSL
