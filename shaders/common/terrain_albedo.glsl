// terrain_albedo.glsl: the ground's albedo from what the height field says about a point — its height
// and slope — and the scene's snow line. Shared with C++ (double) by the rules of compat.glsl, so the
// GPU shading and the CPU reference colour the same ground (terrain/terrain_albedo.h fills the
// parameters from the scene).
//
// Three covers, Lambertian, linear Rec.709 albedos (the scene's /terrain/albedo):
//   rock        everywhere the others are not;
//   vegetation  below the tree line, on slopes gentle enough to hold soil (weight 1 − smoothstep of
//               height across the tree line, times 1 − smoothstep of the slope angle);
//   snow        above the snow line, where the slope is gentle enough for snow to stay (weight
//               smoothstep of height across the snow line, times 1 − smoothstep of the slope angle).
// albedo = mix(mix(rock, vegetation, v), snow, s). Each smoothstep runs over the given transition
// width centred on its threshold. Typical broadband values (Oke 1987, "Boundary Layer Climates",
// 2nd ed., Table 1.1): fresh snow 0.80–0.95, old snow 0.40–0.70, grass 0.16–0.26, coniferous forest
// 0.05–0.15; bare rock 0.1–0.3. Avalanche and rock-fall research puts the steepest slope that holds
// snow near 50–60° (McClung & Schaerer 2006, "The Avalanche Handbook", 3rd ed., ch. 5).
#ifndef FIRMAMENT_TERRAIN_ALBEDO_GLSL
#define FIRMAMENT_TERRAIN_ALBEDO_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

struct TerrainAlbedoParameters {
  vec3 rock;
  vec3 vegetation;
  vec3 snow;
  Real treeLine;              // m above sea level: vegetation fades out across it
  Real treeLineTransition;    // m
  Real vegetationMaxSlope;    // rad: vegetation fades out across it
  Real snowLine;              // m above sea level: snow fades in across it
  Real snowLineTransition;    // m
  Real snowMaxSlope;          // rad: snow fades out across it
  Real slopeTransition;       // rad: width of both slope fades
};

// 1 − smoothstep across [centre − width / 2, centre + width / 2]; a step when width is 0.
SHARED_INLINE Real terrainFadeOut(Real value, Real centre, Real width) {
  Real halfWidth = 0.5 * max(width, 1.0e-6);
  return 1.0 - smoothstep(centre - halfWidth, centre + halfWidth, value);
}

// The weights (vegetation, snow) in [0, 1]² at this height (m) and slope cosine (terrainSlopeCosine).
SHARED_INLINE vec2 terrainCoverWeights(Real height, Real slopeCosine, TerrainAlbedoParameters p) {
  Real slope = acos(clamp(slopeCosine, -1.0, 1.0));
  Real vegetation = terrainFadeOut(height, p.treeLine, p.treeLineTransition) *
                    terrainFadeOut(slope, p.vegetationMaxSlope, p.slopeTransition);
  Real snow = (1.0 - terrainFadeOut(height, p.snowLine, p.snowLineTransition)) *
              terrainFadeOut(slope, p.snowMaxSlope, p.slopeTransition);
  return vec2(vegetation, snow);
}

// The albedo (linear Rec.709) at this height and slope cosine.
SHARED_INLINE vec3 terrainAlbedo(Real height, Real slopeCosine, TerrainAlbedoParameters p) {
  vec2 w = terrainCoverWeights(height, slopeCosine, p);
  return mix(mix(p.rock, p.vegetation, w.x), p.snow, w.y);
}

SHARED_END

#endif  // FIRMAMENT_TERRAIN_ALBEDO_GLSL
