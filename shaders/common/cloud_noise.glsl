// cloud_noise.glsl: the procedural, tileable noise the cloud textures are baked from, shared with C++
// (double) by the rules of compat.glsl. The GPU bakes it into 3D/2D textures from a seed
// (shaders/clouds/bake_*.comp); tests evaluate the same functions on the CPU to check the bake
// (docs/clouds.md, "Noise").
//
// Tileability: every lattice index is wrapped modulo the period (in cells) before it is hashed, so
// f(x + period) = f(x) exactly for every x: the textures repeat without a seam.
// Determinism: integer hashing only (lowbias32, C. Wellons 2018, "Prospecting for hash functions"),
// the same unsigned 32-bit wrap-around arithmetic in GLSL and C++; the seed enters every hash.
#ifndef FIRMAMENT_CLOUD_NOISE_GLSL
#define FIRMAMENT_CLOUD_NOISE_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

// lowbias32: a bijective 32-bit mix with low avalanche bias.
SHARED_INLINE uint noiseHash(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}

// Wraps a lattice coordinate (an integer held in a Real) into [0, period) and returns it as uint.
SHARED_INLINE uint noiseWrap(Real cell, Real period) {
  Real wrapped = cell - period * floor(cell / period);
  return uint(int(wrapped + 0.5));
}

// Hash of a wrapped lattice point and a channel salt.
SHARED_INLINE uint noiseLatticeHash(Real x, Real y, Real z, Real period, uint seed) {
  uint h = noiseHash(seed);
  h = noiseHash(h ^ noiseWrap(x, period));
  h = noiseHash(h ^ (noiseWrap(y, period) * 0x9E3779B1u));
  h = noiseHash(h ^ (noiseWrap(z, period) * 0x85EBCA77u));
  return h;
}

// A hash as a Real in [0, 1): the top 24 bits, exact in float and double.
SHARED_INLINE Real noiseUnit(uint h) { return Real(h >> 8u) * (1.0 / 16777216.0); }

// Perlin's (2002, "Improving noise") quintic fade 6t^5 - 15t^4 + 10t^3.
SHARED_INLINE Real noiseFade(Real t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Gradient from one of Perlin 2002's 12 cube-edge directions, dotted with the offset (x, y, z).
SHARED_INLINE Real noiseGradientDot(uint h, Real x, Real y, Real z) {
  uint k = h % 12u;
  Real u = k < 8u ? x : y;
  Real v = k < 4u ? y : (k == 12u || k == 14u ? x : z);
  return ((k & 1u) == 0u ? u : -u) + ((k & 2u) == 0u ? v : -v);
}

// Periodic gradient noise at p (in cells; period in cells), roughly in [-1, 1].
SHARED_INLINE Real perlinNoise(vec3 p, Real period, uint seed) {
  Real x0 = floor(p.x);
  Real y0 = floor(p.y);
  Real z0 = floor(p.z);
  Real fx = p.x - x0;
  Real fy = p.y - y0;
  Real fz = p.z - z0;
  Real result = 0.0;
  Real u = noiseFade(fx);
  Real v = noiseFade(fy);
  Real w = noiseFade(fz);
  for (int corner = 0; corner < 8; ++corner) {
    Real cx = Real(corner & 1);
    Real cy = Real((corner >> 1) & 1);
    Real cz = Real((corner >> 2) & 1);
    uint h = noiseLatticeHash(x0 + cx, y0 + cy, z0 + cz, period, seed);
    Real weight = (cx > 0.5 ? u : 1.0 - u) * (cy > 0.5 ? v : 1.0 - v) * (cz > 0.5 ? w : 1.0 - w);
    result += weight * noiseGradientDot(h, fx - cx, fy - cy, fz - cz);
  }
  return result;
}

// Periodic cellular noise (Worley 1996), inverted: 1 - F1, with F1 the distance (in cells) to the
// nearest feature point (one per cell, uniformly placed), clamped to [0, 1]. The 27 neighbouring
// cells hold every point that can be nearer than 1 cell.
SHARED_INLINE Real worleyNoise(vec3 p, Real period, uint seed) {
  Real x0 = floor(p.x);
  Real y0 = floor(p.y);
  Real z0 = floor(p.z);
  Real nearest2 = 3.0;
  for (int k = 0; k < 27; ++k) {
    Real cx = x0 + Real(k % 3 - 1);
    Real cy = y0 + Real((k / 3) % 3 - 1);
    Real cz = z0 + Real(k / 9 - 1);
    uint h = noiseLatticeHash(cx, cy, cz, period, seed);
    Real px = cx + noiseUnit(h);
    Real py = cy + noiseUnit(noiseHash(h ^ 0x68E31DA4u));
    Real pz = cz + noiseUnit(noiseHash(h ^ 0xB5297A4Du));
    Real dx = px - p.x;
    Real dy = py - p.y;
    Real dz = pz - p.z;
    nearest2 = min(nearest2, dx * dx + dy * dy + dz * dz);
  }
  return 1.0 - clamp(sqrt(nearest2), 0.0, 1.0);
}

// Perlin fbm of three octaves (frequency doubling, gain 1/2), mapped to [0, 1].
SHARED_INLINE Real perlinFbm01(vec3 p, Real period, uint seed) {
  Real sum = 0.0;
  Real amplitude = 1.0;
  Real frequency = 1.0;
  for (int o = 0; o < 3; ++o) {
    sum += amplitude * perlinNoise(p * frequency, period * frequency, seed + uint(o) * 0x1000193u);
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return clamp(0.5 + 0.5 * sum / 1.75, 0.0, 1.0);
}

// The remap of Schneider 2015 / Häggström 2018 eq. 1: x from [a, b] to [c, d] (no clamping).
SHARED_INLINE Real noiseRemap(Real x, Real a, Real b, Real c, Real d) {
  return c + (x - a) / (b - a) * (d - c);
}

// The shape texture (128^3 RGBA by default) at texel-space position uvw in [0, 1)^3 (one period):
//   G, B, A: inverted Worley with 4, 8 and 16 cells per period;
//   R: Perlin-Worley (Schneider 2015): a 3-octave Perlin fbm (4 cells per period) dilated by the
//      Worley fbm W = 0.625 G + 0.25 B + 0.125 A: R = clamp(remap(perlin, W - 1, 1, 0, 1), 0, 1).
SHARED_INLINE vec4 cloudShapeNoise(vec3 uvw, uint seed) {
  Real g = worleyNoise(uvw * 4.0, 4.0, seed ^ 0x1u);
  Real b = worleyNoise(uvw * 8.0, 8.0, seed ^ 0x2u);
  Real a = worleyNoise(uvw * 16.0, 16.0, seed ^ 0x3u);
  Real worleyFbm = 0.625 * g + 0.25 * b + 0.125 * a;
  Real perlin = perlinFbm01(uvw * 4.0, 4.0, seed ^ 0x4u);
  Real r = clamp(noiseRemap(perlin, worleyFbm - 1.0, 1.0, 0.0, 1.0), 0.0, 1.0);
  return vec4(r, g, b, a);
}

// The detail texture (32^3 RGBA): inverted Worley with 2, 4, 8 and 16 cells per period.
SHARED_INLINE vec4 cloudDetailNoise(vec3 uvw, uint seed) {
  return vec4(worleyNoise(uvw * 2.0, 2.0, seed ^ 0x11u), worleyNoise(uvw * 4.0, 4.0, seed ^ 0x12u),
              worleyNoise(uvw * 8.0, 8.0, seed ^ 0x13u), worleyNoise(uvw * 16.0, 16.0, seed ^ 0x14u));
}

// The curl texture (128^2): the 2D curl (d psi/dy, -d psi/dx) of a periodic Perlin potential psi
// (4 cells per period, two octaves), by central differences over h (in periods); a divergence-free
// field (Bridson et al. 2007, "Curl-noise for procedural fluid flow"), roughly in [-1, 1]^2 after the
// scale 1/(2 pi * 4), returned as (0.5 + 0.5 curl) per component to fit a unorm texture.
SHARED_INLINE Real curlPotential(vec2 uv, uint seed) {
  vec3 p = vec3(uv.x * 4.0, uv.y * 4.0, 0.5);
  return perlinNoise(p, 4.0, seed) + 0.5 * perlinNoise(p * 2.0, 8.0, seed ^ 0x21u);
}

SHARED_INLINE vec4 cloudCurlNoise(vec2 uv, uint seed, Real h) {
  Real dy = (curlPotential(vec2(uv.x, uv.y + h), seed) - curlPotential(vec2(uv.x, uv.y - h), seed)) / (2.0 * h);
  Real dx = (curlPotential(vec2(uv.x + h, uv.y), seed) - curlPotential(vec2(uv.x - h, uv.y), seed)) / (2.0 * h);
  Real scale = 1.0 / (2.0 * kPi * 4.0);
  return vec4(clamp(0.5 + 0.5 * dy * scale, 0.0, 1.0), clamp(0.5 - 0.5 * dx * scale, 0.0, 1.0), 0.5, 1.0);
}

SHARED_END

#endif  // FIRMAMENT_CLOUD_NOISE_GLSL
