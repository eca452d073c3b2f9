#pragma once
// The camera of a sequence's frames, shared by `render --frames` and `timelapse`: a pose, and keyframes
// of poses over the sequence. A frame's scene is the built scene with the frame's elapsed time and pose
// (Sky::setSequenceFrame, firmament/sky.h), never depending on the frames before it, so any frame of a
// sequence can be rebuilt alone (a resumed or sharded time-lapse, docs/timelapse.md).
#include <string>
#include <vector>

#include "firmament/sky.h"

namespace firmament::cli {

// A camera placement (the scene's /camera fields it replaces).
struct CameraPose {
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double height_above_ground_m = 2.0;
  double fov_deg = 75.0;
};

// The camera of the sky's current view.
CameraPose cameraPoseOf(const Sky& sky);
// The pose as the sky's camera (roll from `base`).
SkyCamera skyCameraOf(const CameraPose& pose, const SkyCamera& base);

// Keyframes of the camera over a sequence (timelapse --camera-path FILE), a JSON file:
//   {"keys": [{"time_s": 0, "yaw_deg": 250, "pitch_deg": 8, "height_above_ground_m": 2, "fov_deg": 75}, ...]}
// time_s: seconds of simulated time after the sequence's start, strictly increasing; yaw_deg and pitch_deg
// required, height_above_ground_m and fov_deg default to the scene's camera. Between keys a Catmull-Rom
// spline (C1: no kinks at the keys), yaw along the shorter way round; before the first key the first
// pose, after the last the last. Bad files: InputError naming the file, the key and the allowed values.
class CameraPath {
 public:
  static CameraPath load(const std::string& file, const CameraPose& sceneCamera);
  CameraPose at(double time_s) const;
  const std::string& hash() const { return hash_; }  // of the file's keys (the resume manifest)

 private:
  struct Key {
    double time_s;
    CameraPose pose;
  };
  std::vector<Key> keys_;
  std::string hash_;
};

}  // namespace firmament::cli
