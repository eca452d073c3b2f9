// camera.glsl: pixel -> view ray, shared by the GPU render and the CPU reference so both trace the
// same rays (see compat.glsl). Directions live in the local East-North-Up frame of the ground point
// (x east, y north, z up); the planet centre is at -z.
#ifndef FIRMAMENT_CAMERA_GLSL
#define FIRMAMENT_CAMERA_GLSL

#include "common/compat.glsl"

SHARED_BEGIN

const int kProjectionPerspective = 0;
const int kProjectionFisheye = 1;
const int kProjectionEquirectangular = 2;

struct CameraParameters {
  vec3 forward;     // unit view direction
  vec3 right;       // unit, perpendicular to forward
  vec3 up;          // unit, completes the right-handed basis (right x forward = up)
  Real fov;         // horizontal field of view, rad
  Real yaw;         // rad, clockwise from north (equirectangular centre)
  int projection;
  int width;
  int height;
};

// Basis from yaw (clockwise from north), pitch (above horizontal) and roll (about forward), radians.
SHARED_INLINE void cameraBasis(Real yaw, Real pitch, Real roll, OUT(vec3) forward, OUT(vec3) right, OUT(vec3) up) {
  forward = vec3(sin(yaw) * cos(pitch), cos(yaw) * cos(pitch), sin(pitch));
  vec3 level_right = vec3(cos(yaw), -sin(yaw), 0.0);
  vec3 level_up = cross(level_right, forward);
  right = cos(roll) * level_right + sin(roll) * level_up;
  up = cos(roll) * level_up - sin(roll) * level_right;
}

// Normalised image-plane coordinates of image point `pixel` (perspective and fisheye): x in [-1, 1]
// across the width, y up, scaled by the aspect ratio.
SHARED_INLINE vec2 cameraImagePlane(CameraParameters camera, vec2 pixel) {
  Real w = Real(camera.width);
  Real h = Real(camera.height);
  return vec2(2.0 * pixel.x / w - 1.0, (1.0 - 2.0 * pixel.y / h) * (h / w));
}

// The image point (pixel units) of image-plane coordinates xy: the inverse of cameraImagePlane.
SHARED_INLINE vec2 cameraPixelOfImagePlane(CameraParameters camera, vec2 xy) {
  Real w = Real(camera.width);
  Real h = Real(camera.height);
  return vec2(0.5 * (xy.x + 1.0) * w, 0.5 * (1.0 - xy.y * (w / h)) * h);
}

// Whether image point `pixel` has a ray: false outside a fisheye's image circle (the angle from the
// axis, |xy| fov / 2, past pi), true for the other projections.
SHARED_INLINE bool cameraSeesPixel(CameraParameters camera, vec2 pixel) {
  if (camera.projection != kProjectionFisheye) return true;
  return length(cameraImagePlane(camera, pixel)) * 0.5 * camera.fov <= kPi;
}

// Direction through the point `pixel` (pixel units, (0.5, 0.5) = centre of the top-left pixel).
// `valid` is false outside a fisheye's image circle (cameraSeesPixel).
SHARED_INLINE vec3 cameraRayDirection(CameraParameters camera, vec2 pixel, OUT(bool) valid) {
  valid = true;
  Real w = Real(camera.width);
  Real h = Real(camera.height);
  if (camera.projection == kProjectionEquirectangular) {
    // longitude spans 360 degrees across the width with yaw at the centre; latitude 180 across the height
    Real longitude = camera.yaw + (pixel.x / w - 0.5) * 2.0 * kPi;
    Real latitude = (0.5 - pixel.y / h) * kPi;
    return vec3(cos(latitude) * sin(longitude), cos(latitude) * cos(longitude), sin(latitude));
  }
  vec2 plane = cameraImagePlane(camera, pixel);
  Real x = plane.x;
  Real y = plane.y;
  if (camera.projection == kProjectionFisheye) {
    // Equidistant fisheye: the angle from the axis grows linearly with the distance from the centre.
    Real radius = sqrt(x * x + y * y);
    Real theta = radius * 0.5 * camera.fov;
    if (theta > kPi) {
      valid = false;
      return camera.forward;
    }
    Real s = radius > 0.0 ? sin(theta) / radius : 0.0;
    return normalize(cos(theta) * camera.forward + s * (x * camera.right + y * camera.up));
  }
  Real tan_half = tan(0.5 * camera.fov);
  return normalize(camera.forward + tan_half * (x * camera.right + y * camera.up));
}

// The inverse of cameraRayDirection: the image point (pixel units) whose ray has direction `dir`
// (unit). Temporal reprojection uses it to find where a point seen now was in the previous frame.
// `valid` is false where no pixel looks that way (behind a perspective camera, or at a fisheye's or
// the equirectangular poles' singular point); the point may lie outside the image, which the caller
// checks.
SHARED_INLINE vec2 cameraPixelOfDirection(CameraParameters camera, vec3 dir, OUT(bool) valid) {
  valid = true;
  Real w = Real(camera.width);
  Real h = Real(camera.height);
  if (camera.projection == kProjectionEquirectangular) {
    // Invert longitude = yaw + (x / w - 1/2) 2 pi and latitude = (1/2 - y / h) pi.
    Real horizontal = sqrt(dir.x * dir.x + dir.y * dir.y);
    if (horizontal <= 0.0) {
      valid = false;
      return vec2(0.5 * w, dir.z > 0.0 ? 0.0 : h);
    }
    Real turns = (atan(dir.x, dir.y) - camera.yaw) / (2.0 * kPi);
    turns -= floor(turns + 0.5);  // wrapped to [-1/2, 1/2)
    Real latitude = atan(dir.z, horizontal);
    return vec2((turns + 0.5) * w, (0.5 - latitude / kPi) * h);
  }
  // Components along the camera's basis; image-plane coordinates (x, y) as in cameraRayDirection.
  Real f = dot(dir, camera.forward);
  Real a = dot(dir, camera.right);
  Real b = dot(dir, camera.up);
  Real x, y;
  if (camera.projection == kProjectionFisheye) {
    // Equidistant: the radius in the image plane is theta / (fov / 2), along (a, b).
    Real side = sqrt(a * a + b * b);
    Real theta = atan(side, f);
    Real radius = theta / (0.5 * camera.fov);
    x = side > 0.0 ? radius * a / side : 0.0;
    y = side > 0.0 ? radius * b / side : 0.0;
  } else {
    if (f <= 0.0) {
      valid = false;
      return vec2(-1.0);
    }
    Real tan_half = tan(0.5 * camera.fov);
    x = a / (f * tan_half);
    y = b / (f * tan_half);
  }
  return cameraPixelOfImagePlane(camera, vec2(x, y));
}

SHARED_END

#ifndef __cplusplus
// The camera as the frame, cloud and aerial-perspective uniform blocks carry it (packed on the host
// from SceneView::camera): forward.w = horizontal field of view (rad), right.w = yaw (rad),
// image = (width, height, projection, per-pass use).
CameraParameters cameraFromBlock(vec4 forward, vec4 right, vec4 up, ivec4 image) {
  CameraParameters camera;
  camera.forward = forward.xyz;
  camera.right = right.xyz;
  camera.up = up.xyz;
  camera.fov = forward.w;
  camera.yaw = right.w;
  camera.projection = image.z;
  camera.width = image.x;
  camera.height = image.y;
  return camera;
}
#endif

#endif  // FIRMAMENT_CAMERA_GLSL
