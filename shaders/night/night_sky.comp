#version 450
#extension GL_GOOGLE_include_directive : require
// The night's light added to the sky frame (docs/night.md, "The night in the frame"), before the clouds
// composite over it (so the clouds' transmittance along the view dims all of it):
//  - the moonlit sky and ground: the sky-view table marched with the Moon as the light (the same tables,
//    the Moon's spectrum relative to the Sun's folded into the conversion to Rec.709, sky/night_pass.cpp);
//  - the Moon's disc (common/moon_disc.glsl), supersampled 4x4 where it covers a pixel, extincted by the
//    transmittance along the view;
//  - the stars, splatted energy-conserving on the CPU into a radiance image (sky/night_pass.cpp), and
//    extincted here;
//  - the sky's own light above the air (common/night_sky.glsl: airglow, zodiacal light, faint stars),
//    extincted along the view, plus what the air scatters of it (an isotropic-field estimate).
// Transmittance along the view in Rec.709 is the sun disc's table over its value outside the air: the
// extinction a solar-like spectrum sees in each channel.
#include "atmosphere/atmosphere_block.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"
#include "common/moon_disc.glsl"
#include "common/night_sky.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D sunRadianceLut;
layout(set = 0, binding = 2) uniform sampler2D moonSkyView;
layout(std430, set = 0, binding = 3) buffer OutputFrame { vec4 pixels[]; } outputFrame;
#define SKY_FRAME_BLOCK_BINDING 4
#include "sky/frame_block.glsl"
// std140 mirror of NightBlock in sky/night_pass.cpp.
layout(std140, set = 0, binding = 5) uniform NightBlock {
  vec4 moon_direction;  // xyz unit (ENU); w = apparent angular radius (rad)
  vec4 sun_from_moon;   // xyz unit; w = the lit part's radiance scale C (cd/m^2)
  vec4 moon_colour;     // Rec.709 of unit luminance above the air; w = earthshine luminance (cd/m^2)
  vec4 airglow_rgb[4];  // OI 557.7, Na D, OI 630+636.4, continuum: zenith Rec.709 above the air; w = layer radius
  vec4 solar_rgb;       // Rec.709 of the tabulated solar spectrum per unit "solar spectrum factor"; w = observer radius
  vec4 enu_to_ecliptic[3];  // rows of the rotation ENU -> the Sun's ecliptic frame
  vec4 enu_to_galactic[3];  // rows of the rotation ENU -> galactic
  vec4 scattered_rgb;       // mean top-of-air radiance over the upper hemisphere (Rec.709); w = disc margin (rad)
  ivec4 flags;              // x: moon sky, y: moon disc, z: the sky's own light, w: stars
} night;
layout(std430, set = 0, binding = 6) readonly buffer StarFrame { vec4 pixels[]; } stars;
layout(push_constant) uniform Push { TileDispatch tiles; } push;

vec3 rotateRows(vec4 rows[3], vec3 v) { return vec3(dot(rows[0].xyz, v), dot(rows[1].xyz, v), dot(rows[2].xyz, v)); }

// The sky-view table's texel toward `dir`, the azimuth measured from the light (the Moon).
vec3 moonSky(AtmosphereParameters atmosphere, vec3 origin, vec3 dir, vec3 light) {
  vec3 up = normalize(origin);
  float r = length(origin);
  float theta = acos(clamp(dot(dir, up), -1.0, 1.0));
  vec3 dir_h = dir - dot(dir, up) * up;
  vec3 light_h = light - dot(light, up) * up;
  float norms = length(dir_h) * length(light_h);
  float cos_phi = norms > 1e-8 ? clamp(dot(dir_h, light_h) / norms, -1.0, 1.0) : 1.0;
  return textureLod(moonSkyView, skyViewUvFromAngles(atmosphere, r, theta, cos_phi), 0.0).rgb;
}

void main() {
  uvec2 tile_pixel;
  if (!tilePixel(push.tiles, tile_pixel)) return;
  ivec2 pixel = ivec2(tile_pixel);
  uint index = tile_pixel.y * push.tiles.width + tile_pixel.x;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(pixel) + 0.5, valid);
  if (!valid) return;
  vec3 origin = frame.camera_position.xyz;
  float r = max(length(origin), atmosphere.bottom_radius + 0.01);
  float mu = dir.z;
  vec3 add = vec3(0.0);
  if (night.flags.x != 0) add += moonSky(atmosphere, origin, dir, night.moon_direction.xyz);
  if (!rayIntersectsGround(atmosphere, r, mu)) {
    ivec2 size = textureSize(sunRadianceLut, 0);
    vec3 outside = textureLod(sunRadianceLut, transmittanceUvFromRMu(atmosphere, atmosphere.top_radius, 1.0, size), 0.0).rgb;
    vec3 inside = textureLod(sunRadianceLut, transmittanceUvFromRMu(atmosphere, r, mu, size), 0.0).rgb;
    vec3 transmittance = clamp(inside / max(outside, vec3(1e-30)), vec3(0.0), vec3(1.0));
    vec3 above = vec3(0.0);  // radiance arriving at the top of the air along the view
    if (night.flags.y != 0 && dot(dir, night.moon_direction.xyz) > cos(night.moon_direction.w + night.scattered_rgb.w)) {
      // The disc, 4x4 samples over the pixel: the limb and the terminator keep their area at any size.
      float disc = 0.0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          bool v;
          vec3 d = cameraRayDirection(camera, vec2(pixel) + (vec2(i, j) + 0.5) / 4.0, v);
          disc += moonDiscRadiance(d, night.moon_direction.xyz, night.sun_from_moon.xyz, night.moon_direction.w,
                                   night.sun_from_moon.w, night.moon_colour.w, 1.0);
        }
      above += night.moon_colour.rgb * (disc / 16.0);
    }
    if (night.flags.z != 0) {
      float observer = night.solar_rgb.w;
      for (int k = 0; k < 4; ++k)
        above += night.airglow_rgb[k].rgb * vanRhijnFactor(mu, observer, night.airglow_rgb[k].w);
      vec3 ecliptic = rotateRows(night.enu_to_ecliptic, dir);
      vec3 galactic = rotateRows(night.enu_to_galactic, dir);
      above += night.solar_rgb.rgb *
               (zodiacalSolarSpectrumFactor(ecliptic) + stellarBackgroundSolarSpectrumFactor(galactic.z));
      add += night.scattered_rgb.rgb * (vec3(1.0) - transmittance);
    }
    if (night.flags.w != 0) above += stars.pixels[index].rgb;
    add += above * transmittance;
  }
  vec4 pixel_value = outputFrame.pixels[index];
  outputFrame.pixels[index] = vec4(pixel_value.rgb + max(add, vec3(0.0)), pixel_value.a);
}
