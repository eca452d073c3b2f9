#version 450
#extension GL_GOOGLE_include_directive : require
// Temporal reprojection of the clouds, step 2 (docs/clouds.md "Temporal reprojection"). The march ran
// on a grid k times coarser (k = 2 or 4), grid pixel c on the image pixel k c + o, where the offset o
// cycles through the k x k block over k^2 frames; clouds/temporal_neighbourhood.comp then gave every
// grid pixel its fresh neighbourhood's range, a motion vector and a clamp weight. Every image pixel q
// here takes:
//   - q = k c + o: the fresh sample of c;
//   - otherwise, with history: the previous frame's (L, T) where q's cloud was then, q + 1/2 + the
//     nearest grid pixel's motion vector, read bilinearly (a Catmull-Rom read, against the blur of up
//     to k^2 - 1 resamplings before a pixel is marched again, measured no better: 1.414 % against
//     1.403 % from a still, 640x360, 1/16, 7.5 deg/s, and cost 1.9x this pass on lavapipe), then clamped to that grid
//     pixel's neighbourhood range in proportion to its clamp weight: this rejects history that does not
//     belong here (disocclusion, lighting that changed) without flattening the detail that only the
//     history holds where the reprojection is sure;
//   - without history (first frame, off screen, behind the previous camera): the bilinear
//     interpolation of the fresh samples, as clouds/upsample_clouds.
// Then it composites over the sky: out = T sky + L (clouds are the only thing in front of the sky).
#include "clouds/temporal_block.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(std430, set = 0, binding = 0) readonly buffer FreshClouds { vec4 pixels[]; } fresh;  // rgb: L, a: T (the grid)
// Binding 1 is the grid's depth, read by clouds/temporal_neighbourhood.comp (the two passes share a numbering).
layout(std430, set = 0, binding = 2) readonly buffer History { vec4 pixels[]; } history;  // the previous frame's
layout(std430, set = 0, binding = 3) writeonly buffer CloudFrame { vec4 pixels[]; } cloudFrame;  // this frame's
layout(std430, set = 0, binding = 4) buffer SkyFrame { vec4 pixels[]; } skyFrame;  // read, composited, written
// Per grid pixel (clouds/temporal_neighbourhood.comp): lowest (L, T); highest (L, T); (motion vector in
// pixels, clamp weight, 1 if the previous frame saw its point).
layout(std430, set = 0, binding = 6) readonly buffer Neighbourhood { vec4 records[]; } neighbourhood;
layout(push_constant) uniform Push {
  TileDispatch tiles;  // the image
  int gridWidth;       // the march's grid
  int gridHeight;
  int k;               // the grid is k times coarser
  int clampHistory;    // 1: clamp the history to the fresh neighbourhood
  ivec2 offset;        // this frame's pixel of each k x k block
} push;

vec4 freshAt(ivec2 c) {
  c = clamp(c, ivec2(0), ivec2(push.gridWidth - 1, push.gridHeight - 1));
  return fresh.pixels[c.y * push.gridWidth + c.x];
}

vec4 historyAt(ivec2 p) {
  p = clamp(p, ivec2(0), frame.previous_image.xy - 1);
  return history.pixels[p.y * frame.previous_image.x + p.x];
}

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  ivec2 q = ivec2(tiled);
  uint index = tiled.y * push.tiles.width + tiled.x;
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  if (!cameraSeesPixel(camera, vec2(q) + 0.5)) {  // outside a fisheye's circle: no cloud, the sky as it is (as the march does)
    cloudFrame.pixels[index] = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  // Grid coordinate of q: grid pixel c sits on image pixel k c + o.
  vec2 at = vec2(q - push.offset) / float(push.k);
  ivec2 nearest = ivec2(floor(at + 0.5));
  vec4 value;
  bool found = false;
  if (q == nearest * push.k + push.offset && all(lessThan(nearest, ivec2(push.gridWidth, push.gridHeight)))) {
    value = freshAt(nearest);
    found = true;
  } else {
    // The nearest grid pixel's record: motion vector, clamp weight, whether the previous frame saw it.
    ivec2 cn = clamp(nearest, ivec2(0), ivec2(push.gridWidth - 1, push.gridHeight - 1));
    uint record = 3u * uint(cn.y * push.gridWidth + cn.x);
    vec4 reprojection = neighbourhood.records[record + 2u];
    vec2 p = vec2(q) + 0.5 + reprojection.xy;
    vec2 size = vec2(frame.previous_image.xy);
    if (frame.previous_image.z == kProjectionEquirectangular) p.x -= size.x * floor(p.x / size.x);  // across the seam
    if (reprojection.w > 0.0 && all(greaterThanEqual(p, vec2(0.0))) && all(lessThanEqual(p, size))) {
      vec2 h = p - 0.5;
      ivec2 i0 = ivec2(floor(h));
      vec2 g = h - vec2(i0);
      value = mix(mix(historyAt(i0), historyAt(i0 + ivec2(1, 0)), g.x), mix(historyAt(i0 + ivec2(0, 1)), historyAt(i0 + ivec2(1, 1)), g.x), g.y);
      if (push.clampHistory != 0)
        value = mix(value, clamp(value, neighbourhood.records[record], neighbourhood.records[record + 1u]), reprojection.z);
      found = true;
    }
  }
  if (!found) {  // no history here: the fresh samples, interpolated
    ivec2 cell = ivec2(floor(at));
    vec2 f = at - vec2(cell);
    value = mix(mix(freshAt(cell), freshAt(cell + ivec2(1, 0)), f.x), mix(freshAt(cell + ivec2(0, 1)), freshAt(cell + ivec2(1, 1)), f.x), f.y);
  }
  cloudFrame.pixels[index] = value;
  vec4 sky = skyFrame.pixels[index];
  skyFrame.pixels[index] = vec4(sky.rgb * value.a + value.rgb, sky.a);
}
