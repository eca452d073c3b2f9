#version 450
#extension GL_GOOGLE_include_directive : require
// Temporal reprojection of the clouds (docs/clouds.md "Temporal reprojection"). The march ran on a grid
// k times coarser (k = 2 or 4), grid pixel c on the image pixel k c + o, where the offset o cycles
// through the k x k block over k^2 frames. Every image pixel q here takes:
//   - q = k c + o: the fresh sample of c;
//   - otherwise, with history: the previous frame's (L, T) at the point where q's cloud was then.
//     q's cloud is at P = camera + d dir(q), d the depth of the nearest fresh sample (the march's
//     transmittance-weighted mean depth, or where the ray enters the shells); the cloud field drifts
//     with the wind, so that piece of cloud was at P + motion in the previous frame (motion = the
//     change of the noise's wind offset, common/cloud_density.glsl: the field's features move by
//     -motion); it was seen in the previous camera's pixel cameraPixelOfDirection(P + motion -
//     previous camera) (common/camera.glsl), read bilinearly. The value is clamped to the range
//     (min, max per channel) of the 3 x 3 fresh samples around q, which rejects history that does not
//     belong here (disocclusion, clouds that formed or left, lighting that changed) — Karis 2014's
//     neighbourhood clamp, on the sparse fresh grid — in proportion to how unsure the reprojection is
//     (below), or fully when the sun moved more than 0.25 degrees since the previous frame;
//   - without history (first frame, off screen, behind the previous camera): the bilinear
//     interpolation of the fresh samples, as clouds/upsample_clouds.
// Then it composites over the sky: out = T sky + L (clouds are the only thing in front of the sky).
#include "common/camera.glsl"
#include "common/dispatch.glsl"

layout(local_size_x = FIRMAMENT_TILE_SIZE, local_size_y = FIRMAMENT_TILE_SIZE) in;
layout(std430, set = 0, binding = 0) readonly buffer FreshClouds { vec4 pixels[]; } fresh;  // rgb: L, a: T (the grid)
layout(std430, set = 0, binding = 1) readonly buffer FreshDepth { float depth[]; } freshDepth;  // m (the grid)
layout(std430, set = 0, binding = 2) readonly buffer History { vec4 pixels[]; } history;  // the previous frame's
layout(std430, set = 0, binding = 3) writeonly buffer CloudFrame { vec4 pixels[]; } cloudFrame;  // this frame's
layout(std430, set = 0, binding = 4) buffer SkyFrame { vec4 pixels[]; } skyFrame;  // read, composited, written
layout(std140, set = 0, binding = 5) uniform TemporalBlock {
  vec4 camera_position;  // planet-centred, m
  vec4 camera_forward;   // w = fov
  vec4 camera_right;     // w = yaw
  vec4 camera_up;
  ivec4 image;           // width, height, projection
  vec4 previous_position;
  vec4 previous_forward;
  vec4 previous_right;
  vec4 previous_up;
  ivec4 previous_image;
  vec4 motion;           // xyz: P_previous = P + motion (m); w: the least clamp weight (the sun moved)
} frame;
layout(push_constant) uniform Push {
  TileDispatch tiles;  // the image
  int gridWidth;       // the march's grid
  int gridHeight;
  int k;               // the grid is k times coarser
  int historyOn;       // 0: no usable history (interpolate the fresh samples)
  ivec2 offset;        // this frame's pixel of each k x k block
  int clampHistory;    // 1: clamp the history to the fresh neighbourhood
  int pad;
} push;

vec4 freshAt(ivec2 c) {
  c = clamp(c, ivec2(0), ivec2(push.gridWidth - 1, push.gridHeight - 1));
  return fresh.pixels[c.y * push.gridWidth + c.x];
}

vec4 historyAt(ivec2 p) {
  p = clamp(p, ivec2(0), frame.previous_image.xy - 1);
  return history.pixels[p.y * frame.previous_image.x + p.x];
}

// Catmull-Rom weights of the samples at -1, 0, 1, 2 for a point f in [0, 1) past sample 0 (they sum
// to 1; the outer two are negative, so the result can overshoot: clamped after).
vec4 catmullRomWeights(float f) {
  float f2 = f * f, f3 = f2 * f;
  return vec4(-0.5 * f3 + f2 - 0.5 * f, 1.5 * f3 - 2.5 * f2 + 1.0, -1.5 * f3 + 2.0 * f2 + 0.5 * f, 0.5 * f3 - 0.5 * f2);
}

// Where the point at `depth` along this frame's ray `dir` was seen in the previous frame (pixel units);
// `seen` false where no previous pixel looks that way.
vec2 previousPixel(float depth, vec3 dir, out bool seen) {
  vec3 previousPoint = frame.camera_position.xyz + depth * dir + frame.motion.xyz;
  vec3 toPoint = previousPoint - frame.previous_position.xyz;
  float distance = length(toPoint);
  CameraParameters previous = cameraFromBlock(frame.previous_forward, frame.previous_right, frame.previous_up, frame.previous_image);
  seen = false;
  return distance > 0.0 ? cameraPixelOfDirection(previous, toPoint / distance, seen) : vec2(-1.0);
}

void main() {
  uvec2 tiled;
  if (!tilePixel(push.tiles, tiled)) return;
  ivec2 q = ivec2(tiled);
  uint index = tiled.y * push.tiles.width + tiled.x;
  CameraParameters camera = cameraFromBlock(frame.camera_forward, frame.camera_right, frame.camera_up, frame.image);
  bool valid;
  vec3 dir = cameraRayDirection(camera, vec2(q) + 0.5, valid);
  if (!valid) {  // outside a fisheye's circle: no cloud, the sky as it is (as the march does)
    cloudFrame.pixels[index] = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  // Grid coordinate of q: grid pixel c sits on image pixel k c + o.
  vec2 at = vec2(q - push.offset) / float(push.k);
  ivec2 nearest = ivec2(floor(at + 0.5));
  vec4 value;
  if (q == nearest * push.k + push.offset && all(lessThan(nearest, ivec2(push.gridWidth, push.gridHeight)))) {
    value = freshAt(nearest);
  } else {
    ivec2 cell = ivec2(floor(at));
    vec2 f = at - vec2(cell);
    value = mix(mix(freshAt(cell), freshAt(cell + ivec2(1, 0)), f.x), mix(freshAt(cell + ivec2(0, 1)), freshAt(cell + ivec2(1, 1)), f.x), f.y);
    if (push.historyOn != 0) {
      // The fresh neighbourhood: its range of values (the clamp) and of depths.
      vec4 lo = vec4(1e30), hi = vec4(-1e30);
      float nearDepth = 1e30, farDepth = 0.0;
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
          ivec2 c = clamp(nearest + ivec2(x, y), ivec2(0), ivec2(push.gridWidth - 1, push.gridHeight - 1));
          vec4 s = fresh.pixels[c.y * push.gridWidth + c.x];
          lo = min(lo, s);
          hi = max(hi, s);
          float d = freshDepth.depth[c.y * push.gridWidth + c.x];
          nearDepth = min(nearDepth, d);
          farDepth = max(farDepth, d);
        }
      ivec2 cn = clamp(nearest, ivec2(0), ivec2(push.gridWidth - 1, push.gridHeight - 1));
      bool seen;
      vec2 p = previousPixel(freshDepth.depth[cn.y * push.gridWidth + cn.x], dir, seen);
      vec2 size = vec2(frame.previous_image.xy);
      if (seen && all(greaterThanEqual(p, vec2(0.0))) && all(lessThanEqual(p, size))) {
        // Catmull-Rom over the previous frame's pixel centres (i + 1/2): a pixel is resampled up to
        // k^2 - 1 times before it is marched again, and bilinear resampling's blur adds up.
        vec2 h = p - 0.5;
        ivec2 i0 = ivec2(floor(h));
        vec2 g = h - vec2(i0);
        vec4 wx = catmullRomWeights(g.x), wy = catmullRomWeights(g.y);
        vec4 past = vec4(0.0);
        for (int y = 0; y < 4; ++y) {
          vec4 row = vec4(0.0);
          for (int x = 0; x < 4; ++x) row += wx[x] * historyAt(i0 + ivec2(x - 1, y - 1));
          past += wy[y] * row;
        }
        past = max(past, vec4(0.0));
        past.a = min(past.a, 1.0);
        if (push.clampHistory != 0) {
          // How far apart the history of the neighbourhood's nearest and farthest depths lies: 0 for a
          // turning camera (no parallax), and where the depth is uniform; large at the edges of near
          // clouds when the camera moves or the wind blows, where history of another depth (ghosts)
          // can land. The clamp acts in proportion, fully from one pixel of disagreement: a clamp on
          // the sparse fresh grid everywhere would also flatten the detail that only the history holds.
          bool seenNear, seenFar;
          vec2 spread = previousPixel(nearDepth, dir, seenNear) - previousPixel(farDepth, dir, seenFar);
          float weight = seenNear && seenFar ? clamp(length(spread), 0.0, 1.0) : 1.0;
          // Light that changed everywhere (the sun moved: a time-lapse) needs the clamp everywhere.
          weight = max(weight, frame.motion.w);
          past = mix(past, clamp(past, lo, hi), weight);
        }
        value = past;
      }
    }
  }
  cloudFrame.pixels[index] = value;
  vec4 sky = skyFrame.pixels[index];
  skyFrame.pixels[index] = vec4(sky.rgb * value.a + value.rgb, sky.a);
}
