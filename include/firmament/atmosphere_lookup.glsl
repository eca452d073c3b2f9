// firmament/atmosphere_lookup.glsl: shade a host's own surfaces with Firmament's atmosphere (embedded
// mode, include/firmament/embed.h; docs/api.md, "Atmosphere lookups"). Self-contained GLSL 450: include
// it in a host's shader and bind the two views firmament::Sky::lookups() gives (each with a linear,
// clamp-to-edge sampler, layout VK_IMAGE_LAYOUT_GENERAL) and its parameters (FirmamentAtmosphere, 4 vec4,
// std140 or push constants). Firmament's own composite (shaders/sky/embed_composite.glsl) uses these
// functions for the host's pixels.
//
// Units and frames: distances in m; directions in the camera's local frame (x east, y north, z up at the
// scene's ground point); light in linear Rec.709 cd/m^2 (the sky image's units). The three channels of a
// transmittance are those of 680, 550 and 440 nm, applied to R, G and B as Firmament's clouds do.
//
// The transmittance table (Bruneton 2017, "Precomputed Atmospheric Scattering: a New Implementation",
// section "Transmittance"): T from radius r along a direction of zenith cosine mu to the top of the
// atmosphere, at u = x_mu, v = x_r through texel centres, with rho = sqrt(r^2 - r_b^2),
// H = sqrt(r_t^2 - r_b^2), d = the distance to the top, x_r = rho / H, x_mu = (d - d_min) / (d_max - d_min),
// d_min = r_t - r, d_max = rho + H.
//
// The aerial-perspective volume (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere
// Rendering Technique", section 5.4): the air between the camera and distance d (m along the ray, not a
// view-space z) through image point p (pixel units of the host's colour image, (0, 0) its top-left
// corner). A 3D texture of 3C x R x N texels: C x R columns corner-aligned on the image (column i at
// x = i / (C - 1) width), N slices at d_k = D ((k + 1) / N)^2, three tiles side by side: in-scattered
// sky-like light (cd/m^2), the aerosols' single scattering of sunlight without its phase function
// (multiplied by the Cornette-Shanks phase of the pixel's view-sun angle), the transmittance.
#ifndef FIRMAMENT_ATMOSPHERE_LOOKUP_GLSL
#define FIRMAMENT_ATMOSPHERE_LOOKUP_GLSL

struct FirmamentAtmosphere {
  vec4 radii;  // x: ground radius r_b, y: top radius r_t, z: the camera's radius, w: the volume's depth D (m)
  vec4 sun;    // xyz: unit direction to the sun (camera frame); w: aerosol phase asymmetry g
  vec4 sunIlluminance;  // rgb: the sun's illuminance above the atmosphere (lux, Rec.709); w: 0
  vec4 image;           // xy: the image size the volume's columns follow (pixels); zw: 0
};

// Cornette and Shanks (1992) phase function (1/sr) for the view-sun cosine nu.
float firmamentMiePhase(float g, float nu) {
  float k = 3.0 / (8.0 * 3.14159265358979) * (1.0 - g * g) / (2.0 + g * g);
  float denominator = max(1.0 + g * g - 2.0 * g * nu, 1e-12);
  return k * (1.0 + nu * nu) / (denominator * sqrt(denominator));
}

// Transmittance from radius r (m) along zenith cosine mu to the top of the atmosphere (0 where the ray
// meets the ground is not tested: callers pass an upward mu or check the ground themselves).
vec3 firmamentTransmittanceToTop(sampler2D lut, FirmamentAtmosphere a, float r, float mu) {
  float rb = a.radii.x, rt = a.radii.y;
  vec2 size = vec2(textureSize(lut, 0));
  float H = sqrt(max(rt * rt - rb * rb, 0.0));
  float rho = sqrt(max(r * r - rb * rb, 0.0));
  float b = r * mu, s = sqrt(max(r * r * (mu * mu - 1.0) + rt * rt, 0.0));
  float d = max(b <= 0.0 ? s - b : (rt - r) * (rt + r) / (b + s), 0.0);  // the stable root for mu > 0
  float dMin = rt - r, dMax = rho + H;
  float xMu = dMax > dMin ? clamp((d - dMin) / (dMax - dMin), 0.0, 1.0) : 0.0;
  float xR = H > 0.0 ? clamp(rho / H, 0.0, 1.0) : 0.0;
  vec2 uv = 0.5 / size + vec2(xMu, xR) * (1.0 - 1.0 / size);
  return textureLod(lut, uv, 0.0).rgb;
}

// The sunlight reaching a point `height` m above the ground below the camera's position (a host's
// surface near the camera): the sun's illuminance above the atmosphere times the transmittance towards
// the sun (lux per channel, Rec.709). Curvature over a host's scene is neglected (it is the camera's
// vertical).
vec3 firmamentSunIlluminance(sampler2D lut, FirmamentAtmosphere a, float height) {
  return a.sunIlluminance.rgb * firmamentTransmittanceToTop(lut, a, a.radii.x + max(height, 0.0), a.sun.z);
}

// The air between the camera and distance d (m) along the ray through image point `pixel`, whose
// direction has cosine nu with the sun: in-scattered light (cd/m^2) and transmittance. Three trilinear
// fetches of the volume.
void firmamentAerialPerspective(sampler3D volume, FirmamentAtmosphere a, vec2 pixel, float d, float nu,
                                out vec3 light, out vec3 transmittance) {
  ivec3 size = textureSize(volume, 0);
  int columns = size.x / 3;
  float n = float(size.z), D = a.radii.w;
  float distance = clamp(d, 0.0, D);
  float w = clamp(n * sqrt(distance / D) - 1.0, 0.0, n - 1.0);  // fractional slice index
  float k = min(floor(w), n - 2.0);
  float below = D * ((k + 1.0) / n) * ((k + 1.0) / n);
  float above = D * ((k + 2.0) / n) * ((k + 2.0) / n);
  float z = (k + clamp((distance - below) / (above - below), 0.0, 1.0) + 0.5) / n;
  float near = clamp(distance / (D / (n * n)), 0.0, 1.0);  // linear from the camera to d_0
  float c = clamp(pixel.x / a.image.x, 0.0, 1.0) * float(columns - 1);
  float y = (clamp(pixel.y / a.image.y, 0.0, 1.0) * float(size.y - 1) + 0.5) / float(size.y);
  vec3 skylike = textureLod(volume, vec3((c + 0.5) / float(3 * columns), y, z), 0.0).rgb;
  vec3 aerosol = textureLod(volume, vec3((float(columns) + c + 0.5) / float(3 * columns), y, z), 0.0).rgb;
  vec3 through = textureLod(volume, vec3((float(2 * columns) + c + 0.5) / float(3 * columns), y, z), 0.0).rgb;
  light = near * (skylike + firmamentMiePhase(a.sun.w, nu) * aerosol);
  transmittance = 1.0 - near * (1.0 - through);
}

// A surface's light L (cd/m^2) seen from the camera through d m of air: L T + in-scattered light.
vec3 firmamentApplyAerialPerspective(sampler3D volume, FirmamentAtmosphere a, vec2 pixel, float d, float nu, vec3 L) {
  vec3 light, transmittance;
  firmamentAerialPerspective(volume, a, pixel, d, nu, light, transmittance);
  return L * transmittance + light;
}

#endif  // FIRMAMENT_ATMOSPHERE_LOOKUP_GLSL
