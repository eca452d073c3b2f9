#pragma once
// Firmament's public C++ API (docs/api.md): a sky built from a scene file or scene JSON, then per frame
// a camera, a time and a size in, a linear HDR image and its frame time out. This header includes no
// other Firmament header but firmament/error.h, nor Vulkan. Two ways to run: offline, the sky owns a headless Vulkan
// context and render() returns the image on the CPU; embedded (firmament/embed.h), it adopts a host's Vulkan device and
// record() records into the host's command buffer.
//
//   auto sky = firmament::Sky::Builder().sceneFile("scenes/cumulus.json").build();
//   sky->setCamera({.heightAboveGround_m = 2, .yaw_deg = 180, .pitch_deg = 10});
//   sky->setTime("2026-06-21T18:00:00Z");
//   firmament::SkyFrame frame = sky->render(640, 360);  // frame.rgba: cd/m², 4 floats a pixel
//
// Errors are exceptions derived from std::runtime_error: bad input (a scene field, a quality knob, a
// device name) throws firmament::InputError (firmament/error.h) with a message naming the file, the field
// and the allowed values.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "firmament/error.h"

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

// One pass's GPU time, from Vulkan timestamps.
struct PassTime {
  std::string label;  // "sky/render_sky", "clouds/march", ...
  double milliseconds = 0.0;
};

struct SkyFrame {
  int width = 0;
  int height = 0;
  // Linear Rec.709 RGBA in cd/m², row 0 at the top; A is the clouds' transmittance (1 without clouds).
  std::vector<float> rgba;
  // 4 when the clouds were rendered (A is theirs), 3 otherwise (A is 1): the channels saveExr writes.
  int channels = 4;
  double gpuMilliseconds = 0.0;    // GPU time of the frame's passes (tables excluded)
  double wallMilliseconds = 0.0;   // render() from call to return, tables and download included
  bool continued = false;          // this frame continued the previous one (temporal reprojection allowed)
  bool cloudsReprojected = false;  // the clouds marched a subset of pixels and reprojected the rest
  double sunZenith_deg = 0.0;
  double sunAzimuth_deg = 0.0;
  double moonAltitude_deg = 0.0;         // the Moon's topocentric altitude at the scene's place and time
  double moonIlluminatedFraction = 0.0;  // 0 new .. 1 full

  // What the frame was and what it cost (the stats `firmament render` writes beside the image).
  std::string scene;      // the scene's name: its file, or the built-in default's
  std::string sceneHash;  // of the view's scene with every default filled in (16 hex digits)
  std::string sunSource;  // "time and location" or "scene sun section"
  double sunDistance_au = 1.0;
  std::vector<PassTime> passes;         // GPU time per pass, in execution order
  double precomputeMilliseconds = 0.0;  // GPU time of the tables this frame computed (0 when reused)
  std::string tablesSource;             // the atmosphere's tables: "memory", "disk cache" or "computed"
  int spectralSamples = 3;              // the wavelengths the frame used
  std::string timingNote;               // non-empty when the timings are wall clock, not timestamps
  struct Clouds {
    bool rendered = false;              // the scene has clouds and they were drawn
    double viewSamplesPerPixel = 0.0;   // density evaluations of the view march
    double lightSamplesPerPixel = 0.0;  // and of the light march
    std::string noiseSource;            // "memory", "disk cache" or "baked"
  } clouds;
  struct Night {
    bool run = false;  // the night's passes (Moon, stars, the sky's own light) ran
    double sunAltitude_deg = 0.0, moonAltitude_deg = 0.0;
    bool moonIsTheLight = false;  // the clouds and terrain are lit by the Moon (else the Sun)
    std::string lightReason;
    double sunGroundLux = 0.0, moonGroundLux = 0.0;
  } night;
  // The EXR's string attributes (scene hash, device, per-pass timings, camera, sun: docs/formats.md).
  std::map<std::string, std::string> metadata;
};

// The weather map of a view (scenes with clouds and a weather section): its means and the simulation's run.
struct WeatherSummary {
  bool present = false;  // false: the scene has no weather-driven clouds, the rest is 0
  double meanCoverage = 0.0;
  double cloudyFraction = 0.0;  // of the map's texels with coverage above 0.5
  double meanPrecipitation_mm_h = 0.0;
  double maxTop_m = 0.0;  // the highest cloud top where the coverage is above 0
  std::string startUtc;   // the simulation's start
  double run_h = 0.0;     // from its start to the view's time
};

// UTC times as scenes write them (ISO 8601, "2026-06-21T15:30:00Z"); InputError when malformed or outside
// the ephemerides' range. canonicalUtc: "YYYY-MM-DDThh:mm:ss.sssZ"; utcPlusSeconds: the time s seconds
// later (every day 86400 s); utcSecondsBetween: b - a in seconds, every day 86400 s.
std::string canonicalUtc(const std::string& utc);
std::string utcPlusSeconds(const std::string& utc, double seconds);
double utcSecondsBetween(const std::string& a, const std::string& b);

// Writes the frame to an OpenEXR file (linear, 32-bit float, frame.channels channels, frame.metadata as
// string attributes), atomically.
void saveExr(const SkyFrame& frame, const std::string& path);

// Quality knobs: how finely the renderer computes what the scene describes (the scene says what is there).
// Each is named by a path and set as "/path=value" (the value JSON: a number or a string), like a scene
// field, so the names stay when the renderer's own structures change. qualityKnobs() lists them.
struct QualityKnob {
  std::string path;          // "/atmosphere/view_steps"
  std::string defaultValue;  // as JSON: "32", "\"auto\""
  std::string allowed;       // "an integer from 1 to 4096"
  std::string description;
};
const std::vector<QualityKnob>& qualityKnobs();

// The passes a view needs and those it leaves out, with the reasons (`firmament render --explain`).
struct PlannedPassInfo {
  std::string name;      // the pass and its shader, e.g. "atmosphere/transmittance_lut"
  std::string output;    // what it produces
  std::string reason;    // why this view needs it
  bool perFrame = true;  // false: depends on parameters only, cached by their hash
};
struct LeftOutPass {
  std::string name;
  std::string reason;
};
struct SkyPlan {
  std::string scene;  // the scene's name
  int width = 0, height = 0;
  std::vector<PlannedPassInfo> passes;
  std::vector<LeftOutPass> omitted;      // not needed by this view
  std::vector<LeftOutPass> unavailable;  // asked for by the scene, not implemented in this version
  std::string text;                      // the listing, one pass a line
};

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
    // (/clouds/temporal_update) and unchanged tables are kept. False: every frame is a still, whose clouds
    // average /clouds/march/still_samples jittered sub-frames (frames set by setSequenceFrame march once).
    Builder& temporalReprojection(bool enabled);
    // A quality knob, "/atmosphere/view_steps=64" (qualityKnobs()). Applied in order; InputError at build().
    Builder& quality(const std::string& pathEqualsValue);
    // The plan of the scene as built, with its knobs, without creating a device.
    SkyPlan explain() const;
    // Embedded mode (firmament/embed.h): adopt the host's Vulkan objects instead of creating a context.
    // device() is then ignored; render() is unavailable, record() is the frame.
    Builder& embedded(const EmbeddedDevice& device);
    // Embedded mode: how many frames the host keeps in flight, 1 (default) to 4. record() cycles through
    // that many sets of per-frame resources, so a frame's command buffer may still run while the next
    // count - 1 are recorded; the host waits for a frame before the record() count frames later.
    Builder& framesInFlight(int count);
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

  // A quality knob for the next frames (as Builder::quality); InputError leaves the knobs as they were.
  void setQuality(const std::string& pathEqualsValue);
  std::string quality(const std::string& path) const;  // the knob's value as JSON text
  // The passes the current view needs (what the next render() runs).
  SkyPlan plan() const;

  // A frame of a sequence (`firmament render --frames`, `timelapse`): the view becomes the built scene
  // elapsed_s later with the camera's yaw, pitch, height and field of view. The clouds' clock
  // (/clouds/time_s) advances by elapsed_s and, when the scene has no sun section, so does /time/utc
  // (the sun, moon, stars and weather follow); one weather simulation spans the sequence (it starts at
  // the solar midnight before the built scene's time). Fields set since build() are replaced: a frame
  // depends on the built scene, elapsed_s and the camera only, so any frame can be made alone.
  void setSequenceFrame(double elapsed_s, const SkyCamera& camera);
  void setSequenceFrame(double elapsed_s);  // the built scene's camera
  // Throws the InputError setSequenceFrame would (e.g. more than 7 days of weather), changing nothing.
  void checkSequenceFrame(double elapsed_s, const SkyCamera& camera) const;
  void checkSequenceFrame(double elapsed_s) const;
  // The view's weather map, summarised (computed on the CPU: as costly as a new weather map).
  WeatherSummary weather() const;
  std::string sceneHash() const;  // of the current view's scene, every default filled in (16 hex digits)

  // Renders the view at width x height. With temporal reprojection on, a frame after another of the same
  // size continues it; restartSequence() makes the next frame a still (every pixel marched).
  SkyFrame render(int width, int height);
  // A still of the view whatever the sequence (what `firmament render` of the view gives): every pixel
  // marched, the clouds averaging /clouds/march/still_samples sub-frames; the next render() continues it.
  SkyFrame renderStill(int width, int height);
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
  SkyFrame renderFrame(int width, int height, bool still);
};

}  // namespace firmament
