#version 450
#extension GL_GOOGLE_include_directive : require
// Temporal reprojection, step 1 (docs/clouds.md "Temporal reprojection"): per pixel c of the march's
// sparse grid (on image pixel k c + o), once instead of once per image pixel (k^2 image pixels share it;
// the camera mappings' trigonometry ran for every projection's branch on lavapipe, 3 times per pixel):
//   - the range of the fresh samples over its 3 x 3 neighbourhood, (L, T) per channel: the history
//     clamp's box (Karis 2014's neighbourhood clamp, on the sparse grid);
//   - the motion vector: where its cloud, at the fresh depth d along its ray, was seen in the previous
//     frame (previousPixel), minus where it is now. The image pixels around move with it (the field
//     is smooth over k pixels; the difference is second order in the camera's turn);
//   - the clamp weight: how far apart the neighbourhood's nearest and farthest depths reproject, in
//     previous-frame pixels, saturated at 1 — 0 for a turning camera (no parallax) and wherever the
//     depth is uniform, large at the edges of near clouds when the camera moves or the wind blows,
//     where history of another depth (ghosts) can land; at least the sun-motion weight (motion.w).
#include "clouds/temporal_block.glsl"
#include "common/aerial_perspective.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(std430, set = 0, binding = 0) readonly buffer FreshClouds { vec4 pixels[]; } fresh;  // rgb: L, a: T (the grid)
layout(std430, set = 0, binding = 1) readonly buffer FreshDepth { float depth[]; } freshDepth;  // m (the grid)
// Three vec4 per grid pixel: lowest (L, T); highest (L, T); (motion x, motion y in pixels, clamp weight,
// 1 if the previous frame saw the point else 0).
layout(std430, set = 0, binding = 2) writeonly buffer Neighbourhood { vec4 records[]; } neighbourhood;
layout(push_constant) uniform Push {
  TileDispatch tiles;  // the grid
  ivec2 offset;        // this frame's pixel of each k x k block
  int k;
  int pad;
} push;

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  ivec2 c = ivec2(tiled);
  ivec2 last = ivec2(push.tiles.width, push.tiles.height) - 1;
  vec4 lo = vec4(1e30), hi = vec4(-1e30);
  float nearDepth = 1e30, farDepth = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 n = clamp(c + ivec2(x, y), ivec2(0), last);
      uint i = uint(n.y) * push.tiles.width + uint(n.x);
      vec4 s = fresh.pixels[i];
      lo = min(lo, s);
      hi = max(hi, s);
      float d = freshDepth.depth[i];
      nearDepth = min(nearDepth, d);
      farDepth = max(farDepth, d);
    }
  uint index = tiled.y * push.tiles.width + tiled.x;
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  vec2 point = vec2(c * push.k + push.offset) + 0.5;
  // A fisheye's grid pixels outside its image circle take the rim's direction (aerialColumnDirection),
  // so the image pixels inside the circle whose nearest grid pixel lies outside still get a motion vector.
  bool seen, seenNear, seenFar;
  vec3 dir = aerialColumnDirection(camera, point);
  vec2 motion = previousPixel(freshDepth.depth[index], dir, seen) - point;
  vec2 spread = previousPixel(nearDepth, dir, seenNear) - previousPixel(farDepth, dir, seenFar);
  float weight = seenNear && seenFar ? clamp(length(spread), 0.0, 1.0) : 1.0;
  uint record = 3u * index;
  neighbourhood.records[record] = lo;
  neighbourhood.records[record + 1u] = hi;
  neighbourhood.records[record + 2u] = vec4(motion, max(weight, frame.motion.w), seen ? 1.0 : 0.0);
}
