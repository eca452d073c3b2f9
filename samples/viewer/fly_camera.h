#pragma once
// The viewer's fly camera: WASD moves over the ground (the scene's /location), Q/E down and up
// (/camera/height_above_ground_m), a mouse drag turns (yaw, pitch). Speeds span walking to orbit.
// No window code here: the viewer's input and its scripted replays (samples/viewer/script.h) both call it.
#include <string>

#include "firmament/sky.h"

namespace firmament::viewer {

inline constexpr double kMinSpeed_m_s = 1.0;     // walking
inline constexpr double kMaxSpeed_m_s = 1.0e5;   // above orbital speed (7.8 km/s)
inline constexpr double kDegreesPerPixel = 0.2;  // mouse drag
inline constexpr double kMinHeight_m = 0.1;      // above the ground
inline constexpr double kMaxHeight_m = 1.0e8;    // /camera/height_above_ground_m's limit
inline constexpr double kEarthRadius_m = 6371000.0;

struct FlyState {
  SkyCamera camera;
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double speed_m_s = 10.0;
  // The horizontal distance flown (m, east and north), for the clouds (/clouds/offset_east_m, _north_m):
  // the clouds are placed relative to the ground point, so a flight that only moved the location would
  // carry them along; with the offset they pass by.
  double cloudOffsetEast_m = 0.0;
  double cloudOffsetNorth_m = 0.0;
};

// Movement for held keys, each -1, 0 or 1: forward (W +, S -), right (D +, A -), up (E +, Q -).
struct FlyInput {
  int forward = 0;
  int right = 0;
  int up = 0;
};

// Moves the camera for `seconds` of the held keys at state.speed_m_s. Horizontal moves follow the yaw
// (north = yaw 0) along the ground and change the latitude and longitude (longitude wrapped to
// [-180, 180], latitude clamped to +-89.9) and add the distance to the cloud offset; vertical ones the
// height, clamped to [kMinHeight_m, kMaxHeight_m].
void fly(FlyState& state, const FlyInput& input, double seconds);

// Turns the camera for a mouse drag of (dx, dy) pixels: right turns clockwise, up pitches up (to +-90).
void drag(FlyState& state, double dx, double dy);

// "W", "wasd", "qe": the keys of a script's `key` command as input; InputError for other letters.
FlyInput parseKeys(const std::string& keys);

}  // namespace firmament::viewer
