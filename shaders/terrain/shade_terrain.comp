#version 450
#extension GL_GOOGLE_include_directive : require
// The terrain's shading, once per spectral batch (sky/terrain_pass.h), over the pixels whose ray met the
// terrain (terrain/cast_terrain.comp): the air between the camera and the ground (the clear-sky
// integrand of atmosphere/air_integrand.glsl, marched with the sky's own quadratic steps, so a flat
// terrain at the ground sphere's height is the sky's ground) and the Lambertian ground,
//   L = T_air [ (albedo / pi) (E_sun T_sun (V e^-tau max(n.s, 0) + mu_s D(tau_v, mu_s) S)
//                              + E_sky T_d(tau_v) S) ] + L_air,
// with V the sun's visibility past the terrain, tau the clouds' optical depth along the sun line (Beer
// shadow map), tau_v = tau mu_s their vertical optical depth, D the part of the deck's transmission
// that is diffuse and T_d the deck's transmission of the sky's diffuse light (Eddington's conservative
// slab, docs/terrain.md "Shading"), S the cosine-weighted share of the sky the surface sees past the
// terrain (the cast's: the horizon map's, or (1 + n.z) / 2, an isotropic sky over a tilted surface).
// Clear sky, flat ground: L = T_air (albedo / pi)(E_sun T_sun mu_s + E_sky) + L_air, the sky's ground.
// Light with the sun's spectrum and light with the sky's are converted with their own matrices; the
// albedo (linear Rec.709) multiplies after the conversion.
#include "atmosphere/air_integrand.glsl"
#include "atmosphere/atmosphere_sampling.glsl"
#include "atmosphere/irradiance_sampling.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"
#define TERRAIN_BLOCK_BINDING 1
#define TERRAIN_HEIGHTS_BINDING 2
#define TERRAIN_PYRAMID_BINDING 3
#include "terrain/terrain_block.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 4) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 5) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 6) uniform sampler2D skyIrradianceLut;
layout(set = 0, binding = 7) uniform sampler2D multipleScatteringAnisotropy;
layout(std430, set = 0, binding = 8) readonly buffer TerrainHits { vec4 v[]; }
hits;
layout(std430, set = 0, binding = 9) buffer OutputFrame { vec4 pixels[]; }
outputFrame;
layout(push_constant) uniform Push {
  TileDispatch tiles;
  int accumulate;   // add to the pixel (spectral batches after the first)
  int last;         // the last batch: clamp to >= 0
  int ground_only;  // the ground's radiance at the surface, no air (sky/terrain_pass.h TerrainPassOptions)
  int pad0;
}
push;

void main() {
  uvec2 tile_pixel;
  if (!tilePixel(push.tiles, tile_pixel)) return;
  uint index = tile_pixel.y * push.tiles.width + tile_pixel.x;
  vec4 h0 = hits.v[3u * index];
  if (!(h0.w < 1.0e29)) return;  // no terrain: the sky stays
  vec4 h1 = hits.v[3u * index + 1u];
  vec4 h2 = hits.v[3u * index + 2u];
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera =
      cameraFromBlock(terrain.camera_forward, terrain.camera_right, terrain.camera_up, terrain.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(tile_pixel) + 0.5, valid);
  vec3 sun = terrain.sun_direction.xyz;
  vec3 origin = terrain.camera_position.xyz;
  vec3 normal = h0.xyz;
  float tHit = h0.w;
  vec3 ground = origin + dir * tHit;

  // The air from the camera (or where the ray enters the atmosphere) to the ground.
  float r = length(origin);
  float mu = dot(origin, dir) / r;
  float tStart = 0.0;
  if (r > atmosphere.top_radius && rayIntersectsGround(r, mu, atmosphere.top_radius))
    tStart = distanceToBottomAtmosphereBoundary(r, mu, atmosphere.top_radius);
  vec3 sky = vec3(0.0), sunlike = vec3(0.0), throughput = vec3(1.0);
  float pathLength = max(tHit - tStart, 0.0);
  if (push.ground_only == 0 && (r <= atmosphere.top_radius || tStart > 0.0)) {
    vec3 start = origin + dir * tStart;
    float rStart = max(length(start), atmosphere.bottom_radius + 0.01);
    start = normalize(start) * rStart;
    float nu = dot(dir, sun);
    float phaseR = rayleighPhase(nu);
    float phaseM = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
    int steps = max(terrain.image.w, 1);
    float tPrevious = 0.0;
    for (int i = 1; i <= steps; ++i) {
      float f = float(i) / float(steps);
      float tNext = pathLength * f * f;
      float dt = tNext - tPrevious;
      vec3 p = start + dir * (0.5 * (tPrevious + tNext));
      tPrevious = tNext;
      AirSample air = airSampleAt(atmosphere, transmittanceLut, multipleScatteringLut, multipleScatteringAnisotropy, p,
                                  sun, dir, phaseR, phaseM);
      accumulateAirStep(air, dt, sky, sunlike, throughput);
    }
  }

  // The ground's irradiance (the tables' lookups at least at the atmosphere's ground).
  float rGround = max(length(ground), atmosphere.bottom_radius + 0.01);
  vec3 up = normalize(ground);
  float muS = clamp(dot(up, sun), -1.0, 1.0);
  vec3 sunLight = transmittanceToSun(transmittanceLut, atmosphere, rGround, muS) * atmosphere.solar_irradiance;
  vec3 skyLight = irradianceLookup(skyIrradianceLut, atmosphere, rGround, muS);
  float visibility = h1.x;
  float tau = max(h1.y, 0.0);
  float direct = exp(-tau);
  float diffuseSun = h2.x;  // the deck's (terrain/cast_terrain.comp)
  float diffuseSky = h2.y;
  float skyShare = h1.w;  // S, the share of the sky the surface sees (terrain/cast_terrain.comp)
  float cosine = max(dot(normal, sun), 0.0);
  vec3 groundSun = throughput * sunLight * (visibility * direct * cosine + max(muS, 0.0) * diffuseSun * skyShare) / kPi;
  vec3 groundSky = throughput * skyLight * (diffuseSky * skyShare) / kPi;
  float slopeCosine = clamp(dot(normal, up), -1.0, 1.0);
  vec3 albedo = terrainAlbedo(h1.z, slopeCosine, terrainAlbedoParameters());
  vec3 rgb = skyRadianceToRgb() * sky + sunRadianceToRgb() * sunlike +
             albedo * (sunRadianceToRgb() * groundSun + skyRadianceToRgb() * groundSky);
  if (push.accumulate != 0) rgb += outputFrame.pixels[index].rgb;
  if (push.last != 0) rgb = max(rgb, vec3(0.0));
  outputFrame.pixels[index] = vec4(rgb, 1.0);
}
