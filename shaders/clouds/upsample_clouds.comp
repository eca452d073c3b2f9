#version 450
#extension GL_GOOGLE_include_directive : require
// Reduced-resolution clouds (docs/clouds.md "Resolution"): the march ran on a grid d times coarser in
// x and y (clouds/render_clouds, composite 0), each of its pixels at the centre of the d x d image
// pixels it stands for. Here every image pixel takes the bilinear interpolation of the four nearest
// coarse pixels of (cloud light L, cloud transmittance T) and composites over the sky:
//   out = T sky + L.
// L already carries the air in front of the cloud and T multiplies the sky behind it, so both blend
// linearly: interpolating them is interpolating the composite's two terms. Clouds are the only thing
// in front of the sky, so no depth test is needed.
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(std430, set = 0, binding = 0) readonly buffer CoarseClouds { vec4 pixels[]; } coarse;  // rgb: L, a: T
layout(std430, set = 0, binding = 1) writeonly buffer CloudFrame { vec4 pixels[]; } cloudFrame;  // the image's
layout(std430, set = 0, binding = 2) buffer SkyFrame { vec4 pixels[]; } skyFrame;  // read, composited, written
layout(push_constant) uniform Push {
  TileDispatch tiles;  // the image
  int coarseWidth;
  int coarseHeight;
  int divisor;
  int pad;
} push;

vec4 coarseAt(ivec2 p) {
  p = clamp(p, ivec2(0), ivec2(push.coarseWidth - 1, push.coarseHeight - 1));
  return coarse.pixels[p.y * push.coarseWidth + p.x];
}

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  // Coarse pixel c has its centre at image point d (c + 1/2): image pixel q's centre q + 1/2 is at
  // coarse coordinate (q + 1/2) / d - 1/2.
  vec2 at = (vec2(tiled) + 0.5) / float(push.divisor) - 0.5;
  vec2 cell = floor(at);
  vec2 f = at - cell;
  ivec2 c = ivec2(cell);
  vec4 v = mix(mix(coarseAt(c), coarseAt(c + ivec2(1, 0)), f.x), mix(coarseAt(c + ivec2(0, 1)), coarseAt(c + ivec2(1, 1)), f.x), f.y);
  uint index = tiled.y * push.tiles.width + tiled.x;
  cloudFrame.pixels[index] = v;
  vec4 sky = skyFrame.pixels[index];
  skyFrame.pixels[index] = vec4(sky.rgb * v.a + v.rgb, sky.a);
}
