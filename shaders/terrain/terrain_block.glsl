// terrain_block.glsl (GPU only): what the terrain passes read (sky/terrain_pass.cpp fills it): the
// camera and sun, the height field on the gnomonic plane (common/terrain_geometry.glsl), its min/max
// pyramid (terrain/min_max_pyramid.h) level by level, the clouds' Beer shadow map's placement
// (common/cloud_shadow.glsl) and the albedo's parameters (common/terrain_albedo.glsl).
//
// Define TERRAIN_BLOCK_BINDING, TERRAIN_HEIGHTS_BINDING and TERRAIN_PYRAMID_BINDING before including.
#ifndef FIRMAMENT_TERRAIN_BLOCK_GLSL
#define FIRMAMENT_TERRAIN_BLOCK_GLSL

#include "common/terrain_albedo.glsl"
#include "common/terrain_geometry.glsl"

const int kTerrainMaxLevels = 16;

// std140; mirrored by TerrainBlock in sky/terrain_pass.cpp.
layout(std140, set = 0, binding = TERRAIN_BLOCK_BINDING) uniform TerrainBlock {
  vec4 camera_position;  // planet-centred (m); w = the planet radius R of the heights (sea level)
  vec4 camera_forward;   // xyz; w = horizontal fov (rad)
  vec4 camera_right;     // xyz; w = yaw (rad)
  vec4 camera_up;        // xyz
  vec4 sun_direction;    // xyz, unit; w: 1 = cast shadow rays at the sun (self-shadowing)
  ivec4 image;           // width, height, projection, air march steps
  vec4 grid;             // x0, y0, dx, dy of the samples on the plane (m)
  ivec4 grid_size;       // nx, ny, pyramid levels, 1 when the outside sphere exists
  vec4 heights;          // outside height, highest height (field and outside), sky light (0 deck, 1 clear), tan(sun's angular radius) (0: no penumbra)
  vec4 shadow_centre;    // Beer shadow map: centre (cloud frame, m); w = extent (m)
  vec4 shadow_u;         // axis u; w = start distance L (m)
  vec4 shadow_v;         // axis v; w = 1 when the map is read (clouds with a shadow map)
  vec4 albedo_rock;      // linear Rec.709; w = the clouds' phase asymmetry g for the deck's diffuse light
  vec4 albedo_vegetation;
  vec4 albedo_snow;
  vec4 albedo_lines;     // tree line (m), its transition (m), vegetation's steepest slope (rad), snow line (m)
  vec4 albedo_slopes;    // snow line's transition (m), snow's steepest slope (rad), slope transition (rad), unused
  ivec4 sky_occlusion;   // the sky the terrain hides: mode (0 none, 1 horizon map, 2 rays), rays per pixel, unused, unused
  ivec4 horizon_size;    // horizon map: texels east, texels north, azimuths, unused
  vec4 horizon_grid;     // horizon map: plane position of texel (0, 0), texel spacing east and north (m)
  vec4 deck;             // the clouds' middle radius (m; 0: none), 1 = deck light from the cover the hemisphere sees, unused, unused
  vec4 lod;              // level of detail (terrain/terrain_lod.h): the camera's footprint in cells per metre of distance (0: off), the highest LOD level, unused, unused
  // Per pyramid level L: offset of its group in the pyramid buffer (the minima then maxima of LOD level
  // k's bounds, for k = 0 … min(L, highest LOD level)), width, height, and for 1 <= L <= the highest
  // LOD level the offset of LOD level L's heights in the heights buffer.
  ivec4 levels[kTerrainMaxLevels];
} terrain;

// Horizon elevations (rad, terrain/horizon_map.h): per texel (row-major from the south-west) its
// azimuths' values. Define TERRAIN_HORIZON_BINDING to read them.
#ifdef TERRAIN_HORIZON_BINDING
layout(std430, set = 0, binding = TERRAIN_HORIZON_BINDING) readonly buffer TerrainHorizons { float v[]; } terrainHorizons;
#endif

// Heights (m above R), nx x ny, row-major from the south-west sample; then the LOD levels 1, 2, ...
// (terrain/terrain_lod.h), (width + 1) x (height + 1) of pyramid level k each, at their offsets.
layout(std430, set = 0, binding = TERRAIN_HEIGHTS_BINDING) readonly buffer TerrainHeights { float h[]; } terrainHeights;
// Per level: width x height minima, then width x height maxima (row 0 south).
layout(std430, set = 0, binding = TERRAIN_PYRAMID_BINDING) readonly buffer TerrainPyramid { float v[]; } terrainPyramid;

float terrainAt(int i, int j) { return terrainHeights.h[j * terrain.grid_size.x + i]; }

vec4 terrainCellHeights(int i, int j) {
  return vec4(terrainAt(i, j), terrainAt(i + 1, j), terrainAt(i, j + 1), terrainAt(i + 1, j + 1));
}

vec2 terrainNodeRange(int level, int i, int j) {
  ivec4 l = terrain.levels[level];
  int k = l.x + j * l.y + i;
  return vec2(terrainPyramid.v[k], terrainPyramid.v[k + l.y * l.z]);
}

// The bounds of LOD level k's surface over the pyramid node (level, i, j): from the node's own entry of
// level k's bounds, or, for a node smaller than level k's cells, from the cell it lies in.
vec2 terrainLodNodeRange(int k, int level, int i, int j) {
  if (level < k) {
    i >>= k - level;
    j >>= k - level;
    level = k;
  }
  ivec4 l = terrain.levels[level];
  int n = l.y * l.z;
  int at = l.x + 2 * k * n + j * l.y + i;
  return vec2(terrainPyramid.v[at], terrainPyramid.v[at + n]);
}

// Sample (i, j) of LOD level k >= 1: (width + 1) x (height + 1) samples of pyramid level k's cells.
float terrainLodAt(int k, int i, int j) {
  ivec4 l = terrain.levels[k];
  return terrainHeights.h[l.w + j * (l.y + 1) + i];
}

TerrainAlbedoParameters terrainAlbedoParameters() {
  TerrainAlbedoParameters p;
  p.rock = terrain.albedo_rock.rgb;
  p.vegetation = terrain.albedo_vegetation.rgb;
  p.snow = terrain.albedo_snow.rgb;
  p.treeLine = terrain.albedo_lines.x;
  p.treeLineTransition = terrain.albedo_lines.y;
  p.vegetationMaxSlope = terrain.albedo_lines.z;
  p.snowLine = terrain.albedo_lines.w;
  p.snowLineTransition = terrain.albedo_slopes.x;
  p.snowMaxSlope = terrain.albedo_slopes.y;
  p.slopeTransition = terrain.albedo_slopes.z;
  return p;
}

#endif  // FIRMAMENT_TERRAIN_BLOCK_GLSL
