#include "samples/viewer/fly_camera.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.h"

namespace firmament::viewer {

void fly(FlyState& s, const FlyInput& input, double seconds) {
  const double d = s.speed_m_s * seconds;
  const double yaw = s.camera.yaw_deg * M_PI / 180.0;
  // Forward along the yaw (clockwise from north), right 90 degrees clockwise of it.
  const double north = d * (input.forward * std::cos(yaw) - input.right * std::sin(yaw));
  const double east = d * (input.forward * std::sin(yaw) + input.right * std::cos(yaw));
  const double radius = kEarthRadius_m + s.camera.heightAboveGround_m;
  s.latitude_deg = std::clamp(s.latitude_deg + north / radius * 180.0 / M_PI, -89.9, 89.9);
  const double lon = s.longitude_deg + east / (radius * std::cos(s.latitude_deg * M_PI / 180.0)) * 180.0 / M_PI;
  s.longitude_deg = std::remainder(lon, 360.0);
  s.cloudOffsetEast_m += east;
  s.cloudOffsetNorth_m += north;
  s.camera.heightAboveGround_m = std::clamp(s.camera.heightAboveGround_m + d * input.up, kMinHeight_m, kMaxHeight_m);
}

void drag(FlyState& s, double dx, double dy) {
  double yaw = std::fmod(s.camera.yaw_deg + dx * kDegreesPerPixel, 360.0);
  if (yaw < 0.0) yaw += 360.0;
  s.camera.yaw_deg = yaw;
  s.camera.pitch_deg = std::clamp(s.camera.pitch_deg - dy * kDegreesPerPixel, -90.0, 90.0);
}

FlyInput parseKeys(const std::string& keys) {
  FlyInput input;
  for (char c : keys) {
    switch (std::tolower(static_cast<unsigned char>(c))) {
      case 'w':
        input.forward += 1;
        break;
      case 's':
        input.forward -= 1;
        break;
      case 'd':
        input.right += 1;
        break;
      case 'a':
        input.right -= 1;
        break;
      case 'e':
        input.up += 1;
        break;
      case 'q':
        input.up -= 1;
        break;
      default:
        throw InputError("key '" + std::string(1, c) + "': allowed: W, A, S, D (move), Q, E (down, up)");
    }
  }
  input.forward = std::clamp(input.forward, -1, 1);
  input.right = std::clamp(input.right, -1, 1);
  input.up = std::clamp(input.up, -1, 1);
  return input;
}

}  // namespace firmament::viewer
