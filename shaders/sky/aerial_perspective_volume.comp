#version 450
#extension GL_GOOGLE_include_directive : require
// Aerial-perspective volume (Hillaire 2020, section 5.4), per frame and per spectral batch: for every
// froxel column (one invocation) the air along the camera's ray through the column's image point is
// marched once, from the camera out to the volume's maximum distance D, and the in-scattered light
// (sky-like; the aerosols' single scattering without its phase) and the transmittance accumulated up
// to every slice's far end are written (layout: common/aerial_perspective.glsl). The integrand and the step integration are the sky's
// (atmosphere/air_integrand.glsl: single scattering through the transmittance table with the
// planet's shadow, multiple scattering Psi_ms with its anisotropy), so the volume differs from a
// per-pixel march only by its quadrature (steps per slice) and its interpolation between froxels.
//  - Only the stretch inside the top of the atmosphere is integrated: a camera above it starts at the
//    ray's entry (the slices in front hold no light, T = 1); a ray that misses the atmosphere holds
//    that everywhere.
//  - The ground does not stop a column: beyond it the air is taken at the ground below each sample
//    (radius clamped to the ground's), which continues the column smoothly. No pixel's own ray reads a
//    depth beyond its ground hit, but its neighbours' columns do when it interpolates next to the
//    horizon, and a column frozen at the ground (1-2 km away) would darken clouds 50 km away there.
#include "atmosphere/air_integrand.glsl"
#include "common/aerial_perspective.glsl"
#include "common/cloud_shadow.glsl"
#include "common/geometry.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3) uniform sampler2D multipleScatteringAnisotropy;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image3D volume;  // 3C x R x N (three tiles)
layout(std140, set = 0, binding = 5) uniform AerialBlock {
  vec4 camera_position;  // planet-centred, m; w = maximum distance D (m)
  vec4 camera_forward;   // xyz; w = horizontal fov (rad)
  vec4 camera_right;     // xyz; w = yaw (rad)
  vec4 camera_up;        // xyz
  vec4 sun_direction;    // xyz
  ivec4 image;           // width, height, projection, steps per slice
  ivec4 size;            // columns C, rows R, slices N, unused
  vec4 steps;            // largest scaled-altitude change per step (m; 0: no limit), cap of the scaling (m), unused x2
  vec4 shadow_centre;    // Beer shadow map (common/cloud_shadow.glsl): centre C (cloud frame, m); w = extent (m)
  vec4 shadow_axis_u;    // xyz: axis u; w = start distance L (m)
  vec4 shadow_axis_v;    // xyz: axis v; w = 1: cloud shadows in the air (light shafts), 0: none
} aerial;
layout(set = 0, binding = 6) uniform sampler2D shadowMap;  // the clouds' Beer shadow map (linear, clamp)

// The clouds' transmittance towards the sun at p (1 where the map does not cover p).
float cloudSunVisibility(vec3 p, vec3 sun) {
  vec3 c = cloudShadowCoordinate(p, aerial.shadow_centre.xyz, aerial.shadow_axis_u.xyz, aerial.shadow_axis_v.xyz, sun,
                                 aerial.shadow_centre.w, aerial.shadow_axis_u.w);
  if (!cloudShadowCovers(c)) return 1.0;  // off the map, or sunward of it: no shaft drawn
  return exp(-cloudShadowOpticalDepth(textureLod(shadowMap, c.xy, 0.0), c.z));
}

// Altitude (m) scaled for the step rule: itself up to the cap, an eighth of the rest above it; 0 below
// the ground (samples there take the ground's air).
// Rec.709 luminance of linear RGB.
float rgbLuminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }

float scaledAltitude(float h) {
  float cap = aerial.steps.y;
  return clamp(h, 0.0, cap) + max(h - cap, 0.0) / 8.0;
}

void main() {
  ivec2 column = ivec2(gl_GlobalInvocationID.xy);
  int columns = aerial.size.x, rows = aerial.size.y, slices = aerial.size.z;
  if (column.x >= columns || column.y >= rows) return;
  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera = cameraFromBlock(aerial.camera_forward, aerial.camera_right, aerial.camera_up, aerial.image);
  vec3 dir = aerialColumnDirection(camera, aerialColumnPixel(column.x, column.y, columns, rows, camera.width, camera.height));
  vec3 sun = aerial.sun_direction.xyz;
  float maxDistance = aerial.camera_position.w;
  int stepsPerSlice = max(aerial.image.w, 1);

  // The camera as the cloud march places it (lifted onto the ground if below it).
  vec3 origin = aerial.camera_position.xyz;
  float r = max(length(origin), atmosphere.bottom_radius + 0.01);
  origin = normalize(origin) * r;
  float mu = clamp(dot(origin, dir) / r, -1.0, 1.0);
  // The stretch [t_in, t_out] inside the top of the atmosphere (empty if the ray misses it).
  float t_in = 0.0, t_out = 0.0;
  float near_root, far_root;
  if (raySphereRoots(r, mu, atmosphere.top_radius, near_root, far_root) && far_root > 0.0) {
    t_in = max(near_root, 0.0);
    t_out = far_root;
  }

  // Where the column meets the ground (none: beyond every slice).
  float t_ground = rayIntersectsGround(r, mu, atmosphere.bottom_radius)
                       ? distanceToBottomAtmosphereBoundary(r, mu, atmosphere.bottom_radius)
                       : 2.0 * maxDistance + 1.0;
  float nu = dot(dir, sun);
  float phase_r = rayleighPhase(nu);
  // The aerosols' single scattering is stored without its phase function (the reader applies its
  // own pixel's): phase 1 here.
  const float phase_m = 1.0;
  mat3 skyToRgb = skyRadianceToRgb();
  mat3 sunToRgb = sunRadianceToRgb();
  vec3 sky = vec3(0.0), sunlike = vec3(0.0), throughput = vec3(1.0);
  // Single scattering of sunlight that the clouds' shadows remove (sky-like: Rayleigh; sun-like: the
  // aerosols', without their phase), accumulated as the light is.
  vec3 lostSky = vec3(0.0), lostSunlike = vec3(0.0);
  bool shafts = aerial.shadow_axis_v.w > 0.5;
  float previous = 0.0;
  for (int k = 0; k < slices; ++k) {
    float depth = aerialSliceDepth(k, slices, maxDistance);
    // This slice's stretch of the ray inside the atmosphere, in equal steps (none if it is outside:
    // dt = 0 adds nothing and leaves the throughput). Steps: `steps per slice`, more where the ray
    // climbs or descends, so that no step changes the scaled altitude by more than `max rise` (the
    // medium is exponential in altitude, and a step's midpoint misses its curvature: a camera 10 km
    // up looking down crosses the 1.2 km aerosol scale height every slice). The scaled altitude is
    // the altitude up to the cap (10 km) and an eighth of it above (only molecules, scale height
    // 8 km, and ozone are there). The lowest point of the ray may lie inside the stretch: the change
    // is counted down to it and up again.
    float a = clamp(previous, t_in, t_out);
    float b = clamp(depth, t_in, t_out);
    int n = stepsPerSlice;
    if (aerial.steps.x > 0.0) {
      float t_low = clamp(-r * mu, a, b);
      float h_a = scaledAltitude(length(origin + dir * a) - atmosphere.bottom_radius);
      float h_low = scaledAltitude(length(origin + dir * t_low) - atmosphere.bottom_radius);
      float h_b = scaledAltitude(length(origin + dir * b) - atmosphere.bottom_radius);
      float rise = abs(h_a - h_low) + abs(h_b - h_low);
      n = clamp(int(ceil(rise / aerial.steps.x)), stepsPerSlice, 64);
    }
    // The slice that holds the ground hit is split there (n steps on each side): the medium's
    // altitude has a kink where the column meets the ground, which a step across it would blur.
    float split = clamp(t_ground, a, b);
    for (int part = 0; part < 2; ++part) {
      float lo = part == 0 ? a : split;
      float hi = part == 0 ? split : b;
      int count = hi > lo ? n : 0;
      float dt = max(hi - lo, 0.0) / float(n);
      for (int s = 0; s < count; ++s) {
        vec3 p = origin + dir * (lo + (float(s) + 0.5) * dt);
        float r_p = length(p);
        p *= max(r_p, atmosphere.bottom_radius) / r_p;  // below the ground: the air at the ground
        AirSample air = airSampleAt(atmosphere, transmittanceLut, multipleScatteringLut, multipleScatteringAnisotropy, p,
                                    sun, dir, phase_r, phase_m);
        AirStepWeights weights = airStepWeights(air.extinction, dt);
        if (shafts) {
          // In a cloud's shadow the sun's single scattering falls with the cloud's transmittance; the
          // multiply scattered light (Psi_ms, from the whole sky) is left as it is.
          float shadowed = 1.0 - cloudSunVisibility(p, sun);
          vec3 lostSkySource = air.sky_single_source * shadowed;
          vec3 lostSunSource = air.sunlike_source * shadowed;
          air.sky_source -= lostSkySource;
          air.sunlike_source -= lostSunSource;
          lostSky += throughput * lostSkySource * weights.integral;
          lostSunlike += throughput * lostSunSource * weights.integral;
        }
        accumulateAirStep(air, weights, sky, sunlike, throughput);
      }
    }
    previous = depth;
    // Alpha of tiles 0 and 1: the luminance (cd/m^2) of the light the clouds' shadows removed.
    imageStore(volume, ivec3(column, k), vec4(skyToRgb * sky, rgbLuminance(skyToRgb * lostSky)));
    imageStore(volume, ivec3(column.x + columns, column.y, k), vec4(sunToRgb * sunlike, rgbLuminance(sunToRgb * lostSunlike)));
    imageStore(volume, ivec3(column.x + 2 * columns, column.y, k), vec4(throughput, 1.0));
  }
}
