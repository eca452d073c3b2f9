#pragma once
// Firmament's public C++ API (docs/api.md): a sky built from a scene file or scene JSON, then per frame
// a camera, a time and a size in, a linear HDR image and its frame time out. This header includes no
// other Firmament header, nor Vulkan. Two ways to run: offline, the sky owns a headless Vulkan context
// and render() returns the image on the CPU; embedded (firmament/embed.h), it adopts a host's Vulkan
// device and record() records into the host's command buffer.
//
//   auto sky = firmament::Sky::Builder().sceneFile("scenes/cumulus.json").build();
//   sky->setCamera({.heightAboveGround_m = 2, .yaw_deg = 180, .pitch_deg = 10});
//   sky->setTime("2026-06-21T18:00:00Z");
//   firmament::SkyFrame frame = sky->render(640, 360);  // frame.rgba: cd/m², 4 floats a pixel
//
// Errors are exceptions derived from std::runtime_error: bad input (a scene field, a device name) throws
// firmament::InputError with a message naming the file, the field and the allowed values.
#include <memory>
#include <string>
#include <vector>

namespace firmament {

// Embedded mode's types, defined in firmament/embed.h (which includes Vulkan).
struct EmbeddedDevice;
struct EmbeddedTargets;
struct EmbeddedFrame;
struct AtmosphereLookups;

// The camera, in the local frame of the scene's ground point (/location).
struct SkyCamera {
  double heightAboveGround_m = 2.0;
  double yaw_deg = 0.0;    // clockwise from north
  double pitch_deg = 0.0;  // above the horizontal, -90..90
  double roll_deg = 0.0;
  double fov_deg = 75.0;  // horizontal
};

struct SkyFrame {
  int width = 0;
  int height = 0;
  // Linear Rec.709 RGBA in cd/m², row 0 at the top; A is the clouds' transmittance (1 without clouds).
  std::vector<float> rgba;
  double gpuMilliseconds = 0.0;    // GPU time of the frame's passes (tables excluded)
  double wallMilliseconds = 0.0;   // render() from call to return, tables and download included
  bool continued = false;          // this frame continued the previous one (temporal reprojection allowed)
  bool cloudsReprojected = false;  // the clouds marched a subset of pixels and reprojected the rest
  double sunZenith_deg = 0.0;
  double sunAzimuth_deg = 0.0;
};

// Writes frame.rgba to an OpenEXR file (linear, 32-bit float RGBA).
void saveExr(const SkyFrame& frame, const std::string& path);

class Sky {
 public:
  class Builder {
   public:
    Builder();
    ~Builder();
    Builder& sceneFile(const std::string& path);  // a scene file (docs/scene.md)
    Builder& sceneJson(const std::string& text);  // scene text; without either, scenes/default.json
    // A scene field by JSON pointer, as `--set`: "/clouds/quality=low". Applied in order.
    Builder& set(const std::string& pointerEqualsValue);
    Builder& device(const std::string& nameOrIndex);  // as --device; "" (default): a GPU if any, else lavapipe
    // True (default): consecutive render() calls form a sequence: the clouds reproject the previous frame
    // (/clouds/temporal_update) and unchanged tables are kept. False: every frame is a still.
    Builder& temporalReprojection(bool enabled);
    // Embedded mode (firmament/embed.h): adopt the host's Vulkan objects instead of creating a context.
    // device() is then ignored; render() is unavailable, record() is the frame.
    Builder& embedded(const EmbeddedDevice& device);
    std::unique_ptr<class Sky> build();

   private:
    struct Settings;
    std::unique_ptr<Settings> settings_;
  };

  ~Sky();
  Sky(const Sky&) = delete;
  Sky& operator=(const Sky&) = delete;

  void setCamera(const SkyCamera& camera);
  SkyCamera camera() const;
  void setTime(const std::string& utc);  // ISO 8601, "2026-06-21T15:30:00Z"
  void setLocation(double latitude_deg, double longitude_deg);
  // Any scene field, validated now: "/clouds/layers/0/coverage=0.8". Throws InputError when invalid
  // (the view stays as it was).
  void set(const std::string& pointerEqualsValue);
  // The value of a scene field (defaults filled in) as JSON text, "" when the scene has no such field.
  std::string get(const std::string& pointer) const;

  // Renders the view at width x height. With temporal reprojection on, a frame after another of the same
  // size continues it; restartSequence() makes the next frame a still (every pixel marched).
  SkyFrame render(int width, int height);
  void restartSequence();

  // Embedded mode (firmament/embed.h): records the frame into targets.commandBuffer, compositing over
  // the host's colour at its depth. Throws InputError for bad targets or in offline mode.
  EmbeddedFrame record(const EmbeddedTargets& targets);
  // The transmittance and aerial-perspective tables of the last record(), for the host's shaders.
  AtmosphereLookups lookups() const;

  // The current view as a scene file (camera, time, place and every other field): `firmament render` of
  // it reproduces a still of this view.
  std::string sceneJson() const;
  std::string deviceDescription() const;  // "llvmpipe (LLVM 15.0.6, 256 bits), CPU, ..."
  // Vulkan validation messages so far (FIRMAMENT_VALIDATION=1); empty when validation is off.
  std::vector<std::string> validationMessages() const;

 private:
  struct Impl;
  explicit Sky(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace firmament
