#version 450
#extension GL_GOOGLE_include_directive : require
// Clear-sky render from Bruneton 2017's precomputed tables (his GetSkyRadiance and
// GetSkyRadianceToPoint): no march, a few lookups per pixel.
//   sky ray:     L = S(x, w) p_R(nu) + S_M(x, w) p_M(nu) + T(x, top) L_sun_disc
//   ground ray:  L = [S(x, w) - T(x, g) S(g, w)] p_R(nu) + [S_M(x, w) - T(x, g) S_M(g, w)] p_M(nu)
//                    + T(x, g) rho/pi (E_sun T_sun(g) max(mu_s_g, 0) + E_sky(g))
// S holds single Rayleigh plus every multiple order divided by p_R (see multiple_scattering.comp),
// interpolated geometrically along mu_s (scattering_sampling.glsl: smooth twilight),
// S_M single Mie; the light scattered on the stretch between x and the ground point g is what reaches
// x from the whole ray minus what reaches g from beyond it, attenuated to x. Radiance at the three
// wavelengths is converted to Rec.709 cd/m^2 as render_sky.comp does: the sky matrix for Rayleigh and
// multiple scattering (and the ground's reflection of skylight), the sun matrix for single Mie, the
// ground's reflection of sunlight and the sun disc.
//
// One dispatch per spectral batch (its own tables and conversion matrices): push.blend.z says how the
// batch's Rec.709 radiance L_b enters the frame: 0 writes it, 1 adds w L_b, 2 replaces the frame's f_ms
// sky F by (1 - w) F + w L_b (the hand-over through dusk, sky/render_plan.h's twilightTablesWeight), w =
// push.blend.y. push.blend.x rescales what the tables hold to the current solar irradiance (the Sun's
// distance; the tables are linear in it and keep the scale they were computed at).
#include "atmosphere/irradiance_sampling.glsl"
#include "atmosphere/scattering_sampling.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler3D scatteringTable;
layout(set = 0, binding = 3) uniform sampler3D singleMieTable;
layout(set = 0, binding = 4) uniform sampler2D irradianceTable;
layout(std430, set = 0, binding = 5) buffer OutputFrame { vec4 pixels[]; } outputFrame;  // row-major
#define SKY_FRAME_BLOCK_BINDING 6
#include "sky/frame_block.glsl"
layout(push_constant) uniform Push { TileDispatch tiles; ivec4 table_size; vec4 blend; } push;

// The sun's disc at the top of the atmosphere: E_sun I(1)/E times the shared limb darkening
// (common/atmosphere_medium.glsl), the same profile as the f_ms path and the reference.
vec3 sunDiscRadiance(AtmosphereParameters atmosphere, float cos_angle) {
  return atmosphere.solar_irradiance * sunDiscCentreFactor(atmosphere.sun_angular_radius) *
         sunLimbDarkening(cos_angle, atmosphere.sun_angular_radius);
}

void main() {
  uvec2 tile_pixel;
  if (!tilePixel(push.tiles, tile_pixel)) return;
  ivec2 pixel = ivec2(tile_pixel);

  AtmosphereParameters atmosphere = atmosphereFromBlock();
  ScatteringTableSize tableSize = ScatteringTableSize(push.table_size.x, push.table_size.y, push.table_size.z, push.table_size.w);
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(pixel) + 0.5, valid);
  const uint index = tile_pixel.y * push.tiles.width + tile_pixel.x;
  const int mode = int(push.blend.z);
  if (!valid) {
    if (mode == 0) outputFrame.pixels[index] = vec4(0.0);
    return;
  }
  const float tableScale = push.blend.x;
  vec3 sun = frame.sun_direction.xyz;
  float nu = dot(dir, sun);
  vec3 origin = frame.camera_position.xyz;
  float r = length(origin);
  float mu = dot(origin, dir) / r;

  vec3 sky = vec3(0.0);      // sky spectrum: Rayleigh + multiple orders, reflected skylight
  vec3 sunlike = vec3(0.0);  // solar spectrum: single Mie, reflected sunlight
  vec3 throughput = vec3(1.0);
  bool hitsGround = false;
  bool inAtmosphere = true;
  if (r > atmosphere.top_radius) {
    // From space: the tables start at the top, so move the camera to where the ray enters the
    // atmosphere (the near root of the top sphere), or see only the sun when it never does.
    if (!rayIntersectsGround(r, mu, atmosphere.top_radius)) {
      inAtmosphere = false;
    } else {
      origin += dir * distanceToBottomAtmosphereBoundary(r, mu, atmosphere.top_radius);
      r = length(origin);
      mu = dot(origin, dir) / r;
    }
  }
  // Below the ground sphere, see from the ground (as render_sky.comp).
  r = clamp(r, atmosphere.bottom_radius + 0.01, atmosphere.top_radius);
  mu = clampCosine(mu);
  float mu_s = clampCosine(dot(normalize(origin), sun));

  if (inAtmosphere) {
    float phaseR = rayleighPhase(nu);
    float phaseM = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
    hitsGround = rayIntersectsGround(atmosphere, r, mu);
    vec3 scattering = scatteringAtGeometricMuS(scatteringTable, atmosphere, tableSize, r, mu, mu_s, nu, hitsGround);
    vec3 singleMie = scatteringAtGeometricMuS(singleMieTable, atmosphere, tableSize, r, mu, mu_s, nu, hitsGround);
    if (!hitsGround) {
      throughput = transmittanceToTop(transmittanceLut, atmosphere, r, mu);
    } else {
      float d = distanceToBottomAtmosphereBoundary(atmosphere, r, mu);
      float r_g, mu_g, mu_s_g;
      pointAlongRay(r, mu, mu_s, nu, d, r_g, mu_g, mu_s_g);
      r_g = max(r_g, atmosphere.bottom_radius);
      throughput = transmittanceBetween(transmittanceLut, atmosphere, r, mu, d, true);
      scattering = max(scattering - throughput * scatteringAtGeometricMuS(scatteringTable, atmosphere, tableSize, r_g, mu_g, mu_s_g, nu, true), vec3(0.0));
      singleMie = max(singleMie - throughput * scatteringAtGeometricMuS(singleMieTable, atmosphere, tableSize, r_g, mu_g, mu_s_g, nu, true), vec3(0.0));
      // Bruneton's guard for the difference of two Mie lookups, which is unreliable once the sun
      // has set at the camera (the single Mie of the stretch is then negligible anyway).
      singleMie *= smoothstep(0.0, 0.01, mu_s);
      vec3 reflectance = atmosphere.ground_albedo / kPi;
      sunlike += throughput * reflectance * directIrradiance(transmittanceLut, atmosphere, r_g, mu_s_g);
      sky += throughput * reflectance * (tableScale * irradianceLookup(irradianceTable, atmosphere, r_g, mu_s_g));
    }
    sky += tableScale * scattering * phaseR;
    sunlike += tableScale * singleMie * phaseM;
  }
  vec3 rgb = skyRadianceToRgb() * sky + sunRadianceToRgb() * sunlike;
  if (!hitsGround) rgb += sunRadianceToRgb() * (throughput * sunDiscRadiance(atmosphere, nu));
  rgb = max(rgb, vec3(0.0));
  const float w = push.blend.y;
  if (mode == 0)
    outputFrame.pixels[index] = vec4(rgb, 1.0);
  else if (mode == 1)
    outputFrame.pixels[index].rgb += w * rgb;
  else
    outputFrame.pixels[index] = vec4(mix(outputFrame.pixels[index].rgb, rgb, w), 1.0);
}
