#pragma once
// The scene of one frame of a sequence, shared by `render --frames` and `timelapse`: the scene file with
// its overrides, read again with the frame's clock and camera. A frame's scene depends only on the base
// scene and the frame's elapsed time and pose, never on the frames before it, so any frame of a sequence
// can be rebuilt alone (a resumed or sharded time-lapse, docs/timelapse.md).
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace firmament::cli {

// Where a sequence's scenes come from.
struct SequenceSceneSource {
  std::string path;                    // the scene file; empty: the built-in default scene
  std::vector<std::string> overrides;  // --set and the tool's own (/camera/width, /time/utc, ...)
  // The scene with `overrides` and then `extra` applied.
  Scene load(const std::vector<std::string>& extra = {}) const;
};

// A camera placement (the scene's /camera fields it replaces).
struct CameraPose {
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double height_above_ground_m = 2.0;
  double fov_deg = 75.0;
};

// The camera of `scene`.
CameraPose cameraPoseOf(const Scene& scene);

// The scene `elapsed_s` after `base` (which `source` loads): the clouds' clock /clouds/time_s advances by
// elapsed_s and, when the scene has no sun section (the sun follows time and location), so does /time/utc
// (sun, moon, stars and the weather simulation follow); `pose`, when given, replaces the camera.
Scene sequenceFrameScene(const SequenceSceneSource& source, const Scene& base, double elapsed_s,
                         const std::optional<CameraPose>& pose);

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
