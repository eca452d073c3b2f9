#version 450
#extension GL_GOOGLE_include_directive : require
// Clear-sky render: per pixel, integrate single scattering plus Hillaire 2020's multiple-scattering
// term along the view ray, add the ground and the sun disc, and convert to linear Rec.709 cd/m².
//   L = ∫_0^D T(0,t) [ sigma_s^R(t) p_R(nu) + sigma_s^M(t) p_M(nu) ] E_sun T_sun(t)
//                  + [ sigma_s^R(t) + sigma_s^M(t) ] Psi_ms(t)  dt
//     + T(0,D) L_ground                                   (if the ray meets the ground: sun + sky irradiance)
//     + T(0,D) L_sun_disc                                 (inside the sun's disc)
// Each step is integrated analytically for constant coefficients (Hillaire 2016's energy-conserving
// form), and samples are spaced quadratically to resolve the dense air near the camera.
#include "atmosphere/atmosphere_sampling.glsl"
#include "atmosphere/irradiance_sampling.glsl"
#include "common/camera.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(set = 0, binding = 1) uniform sampler2D transmittanceLut;
layout(set = 0, binding = 2) uniform sampler2D multipleScatteringLut;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D outputImage;
layout(std140, set = 0, binding = 4) uniform FrameBlock {
  vec4 camera_position;  // planet-centred, m (the ground point's ENU axes)
  vec4 camera_forward;   // xyz; w = horizontal fov (rad)
  vec4 camera_right;     // xyz; w = yaw (rad)
  vec4 camera_up;        // xyz
  vec4 sun_direction;    // xyz, unit
  ivec4 image;           // width, height, projection, view march steps
} frame;
// The sky's irradiance on the ground, E_sky(r, mu_s) (atmosphere/fms_sky_irradiance.comp).
layout(set = 0, binding = 5) uniform sampler2D skyIrradianceLut;
layout(push_constant) uniform Push { TileDispatch tiles; } push;

// Limb darkening I(mu)/I(1) = mu^alpha (a power law, Hestroffer & Magnan 1998) with alpha ~ 0.5 at
// visible wavelengths; the disc radiance is normalised so the disc integrates to E_sun:
// ∫ I dOmega = I(1) pi a^2 * 2/(alpha+2)  =>  I(1) = E_sun (alpha+2) / (2 pi a^2).
const float kLimbDarkeningAlpha = 0.5;

vec3 sunDiscRadiance(AtmosphereParameters atmosphere, float cos_angle) {
  float a = atmosphere.sun_angular_radius;
  float cos_a = cos(a);
  if (cos_angle < cos_a) return vec3(0.0);
  float angle = acos(clamp(cos_angle, -1.0, 1.0));
  float rho = clamp(angle / a, 0.0, 1.0);  // fraction of the disc radius
  float mu = sqrt(max(1.0 - rho * rho, 0.0));
  float centre = (kLimbDarkeningAlpha + 2.0) / (2.0 * kPi * a * a);
  return atmosphere.solar_irradiance * centre * pow(mu, kLimbDarkeningAlpha);
}

void main() {
  // Tiles in interleaved order on lavapipe (balances sky against ground), row order on GPUs.
  uvec2 tile_pixel;
  if (!tilePixel(push.tiles, tile_pixel)) return;
  ivec2 pixel = ivec2(tile_pixel);

  AtmosphereParameters atmosphere = atmosphereFromBlock();
  CameraParameters camera;
  camera.forward = frame.camera_forward.xyz;
  camera.right = frame.camera_right.xyz;
  camera.up = frame.camera_up.xyz;
  camera.fov = frame.camera_forward.w;
  camera.yaw = frame.camera_right.w;
  camera.projection = frame.image.z;
  camera.width = frame.image.x;
  camera.height = frame.image.y;
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(pixel) + 0.5, valid);
  if (!valid) {
    imageStore(outputImage, pixel, vec4(0.0));
    return;
  }
  vec3 sun = frame.sun_direction.xyz;
  float nu = dot(dir, sun);

  vec3 origin = frame.camera_position.xyz;
  float r = length(origin);
  float mu = dot(origin, dir) / r;
  vec3 sky = vec3(0.0);
  // Light with a solar spectrum (aerosol single scattering, which is nearly grey for Angstrom alpha
  // near 0, and the ground's reflection of sunlight) is converted with the sun's factors; Rayleigh and
  // multiple scattering with the sky's (see atmosphere/atmosphere_spectra.h).
  vec3 sunlike = vec3(0.0);
  vec3 throughput = vec3(1.0);
  bool hits_ground = false;
  bool in_atmosphere = true;
  if (r > atmosphere.top_radius) {
    // From space: jump to where the ray enters the atmosphere, if it does.
    if (!rayIntersectsGround(r, mu, atmosphere.top_radius)) {
      in_atmosphere = false;
    } else {
      origin += dir * distanceToBottomAtmosphereBoundary(r, mu, atmosphere.top_radius);
      r = atmosphere.top_radius;
      mu = dot(origin, dir) / length(origin);
    }
  }
  // A camera below the ground sphere sees from the ground (there is nothing to render below it).
  r = max(r, atmosphere.bottom_radius + 0.01);
  if (in_atmosphere) {
    hits_ground = rayIntersectsGround(atmosphere, r, mu);
    float path_length = distanceToNearestAtmosphereBoundary(atmosphere, r, mu);
    int steps = max(frame.image.w, 1);
    float phase_r = rayleighPhase(nu);
    float phase_m = cornetteShanksPhase(atmosphere.mie_phase_g, nu);
    float t_previous = 0.0;
    vec3 start = normalize(origin) * r;
    for (int i = 1; i <= steps; ++i) {
      // quadratic spacing: t_i = D (i/N)^2; sample the step's midpoint
      float f = float(i) / float(steps);
      float t_next = path_length * f * f;
      float dt = t_next - t_previous;
      vec3 p = start + dir * (0.5 * (t_previous + t_next));
      t_previous = t_next;
      float r_p = length(p);
      float mu_s_p = dot(p, sun) / r_p;
      vec3 rayleigh = rayleighScatteringAt(atmosphere, r_p);
      vec3 mie = mieScatteringAt(atmosphere, r_p);
      vec3 extinction = extinctionAt(atmosphere, r_p);
      vec3 sun_light = transmittanceToSun(transmittanceLut, atmosphere, r_p, mu_s_p) * atmosphere.solar_irradiance;
      vec3 sky_source = rayleigh * phase_r * sun_light +
                        (rayleigh + mie) * multipleScattering(multipleScatteringLut, atmosphere, r_p, mu_s_p);
      vec3 sunlike_source = mie * phase_m * sun_light;
      vec3 step_transmittance = exp(-extinction * dt);
      vec3 k = extinction * dt;
      vec3 integral = mix(dt * (1.0 - step_transmittance) / max(k, vec3(1e-12)), vec3(dt), lessThan(k, vec3(1e-4)));
      sky += throughput * sky_source * integral;
      sunlike += throughput * sunlike_source * integral;
      throughput *= step_transmittance;
    }
    if (hits_ground) {
      vec3 p = start + dir * path_length;
      float r_g = length(p);
      float mu_s_g = dot(p, sun) / r_g;
      vec3 sun_light = transmittanceToSun(transmittanceLut, atmosphere, r_g, mu_s_g) * atmosphere.solar_irradiance;
      sunlike += throughput * atmosphere.ground_albedo / kPi * sun_light * max(mu_s_g, 0.0);
      // Skylight reflected by the ground has the sky's spectrum: converted with the sky's factors.
      sky += throughput * atmosphere.ground_albedo / kPi * irradianceLookup(skyIrradianceLut, atmosphere, r_g, mu_s_g);
    }
  }
  vec3 rgb = skyRadianceToRgb() * sky + sunRadianceToRgb() * sunlike;
  if (!hits_ground) rgb += sunRadianceToRgb() * (throughput * sunDiscRadiance(atmosphere, nu));
  imageStore(outputImage, pixel, vec4(max(rgb, vec3(0.0)), 1.0));
}
