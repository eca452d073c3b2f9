// firmament::Sky (include/firmament/sky.h) over SkyRenderer: the scene as a JSON document that the
// setters edit and Scene::parse validates, one Vulkan context and renderer per sky.
#include "firmament/sky.h"

#include <cstring>

#include "firmament/embed.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include "core/error.h"
#include "core/exr_io.h"
#include "core/scene.h"
#include "gpu/context.h"
#include "sky/sky_renderer.h"

namespace firmament {

struct Sky::Builder::Settings {
  std::optional<std::string> file;
  std::optional<std::string> text;
  std::vector<std::string> overrides;
  std::string device;
  bool temporal = true;
  std::optional<gpu::AdoptedDevice> adopted;  // embedded mode
};

Sky::Builder::Builder() : settings_(std::make_unique<Settings>()) {}
Sky::Builder::~Builder() = default;
Sky::Builder& Sky::Builder::sceneFile(const std::string& path) {
  settings_->file = path;
  settings_->text.reset();
  return *this;
}
Sky::Builder& Sky::Builder::sceneJson(const std::string& text) {
  settings_->text = text;
  settings_->file.reset();
  return *this;
}
Sky::Builder& Sky::Builder::set(const std::string& pointerEqualsValue) {
  settings_->overrides.push_back(pointerEqualsValue);
  return *this;
}
Sky::Builder& Sky::Builder::device(const std::string& nameOrIndex) {
  settings_->device = nameOrIndex;
  return *this;
}
Sky::Builder& Sky::Builder::embedded(const EmbeddedDevice& d) {
  settings_->adopted = gpu::AdoptedDevice{d.instance, d.physicalDevice, d.device, d.queueFamily, d.queue};
  return *this;
}
Sky::Builder& Sky::Builder::temporalReprojection(bool enabled) {
  settings_->temporal = enabled;
  return *this;
}

struct Sky::Impl {
  Impl(const gpu::ContextOptions& options, const std::optional<gpu::AdoptedDevice>& adopted, Scene initial)
      : context(adopted ? std::make_unique<gpu::Context>(*adopted, options) : std::make_unique<gpu::Context>(options)),
        renderer(*context),
        scene(std::move(initial)),
        document(scene.root()) {}
  std::unique_ptr<gpu::Context> context;
  SkyRenderer renderer;
  Scene scene;              // the validated view
  nlohmann::json document;  // its JSON (defaults filled in), what the setters edit
  bool temporal = true;
  bool continueNext = false;
  int lastWidth = 0, lastHeight = 0;

  // Validates an edited document and makes it the view; on error the view stays as it was.
  void commit(nlohmann::json edited) {
    scene = Scene::parse(edited.dump(), scene.source());
    document = scene.root();
  }
};

std::unique_ptr<Sky> Sky::Builder::build() {
  const Settings& s = *settings_;
  Scene scene = s.file   ? Scene::load(*s.file, s.overrides)
                : s.text ? Scene::parse(*s.text, "<scene json>", s.overrides)
                         : Scene::parse(defaultSceneText(), kDefaultSceneName, s.overrides);
  gpu::ContextOptions options;
  options.device = s.device;
  if (s.adopted) options.validation = false;  // the host's instance: its own messenger sees the messages
  auto impl = std::make_unique<Impl>(options, s.adopted, std::move(scene));
  impl->temporal = s.temporal;
  return std::unique_ptr<Sky>(new Sky(std::move(impl)));
}

Sky::Sky(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Sky::~Sky() = default;

void Sky::setCamera(const SkyCamera& c) {
  nlohmann::json d = impl_->document;
  nlohmann::json& camera = d["camera"];
  camera["height_above_ground_m"] = c.heightAboveGround_m;
  camera["yaw_deg"] = c.yaw_deg;
  camera["pitch_deg"] = c.pitch_deg;
  camera["roll_deg"] = c.roll_deg;
  camera["fov_deg"] = c.fov_deg;
  impl_->commit(std::move(d));
}

SkyCamera Sky::camera() const {
  const Scene& s = impl_->scene;
  return {s.number("/camera/height_above_ground_m"), s.number("/camera/yaw_deg"), s.number("/camera/pitch_deg"),
          s.number("/camera/roll_deg"), s.number("/camera/fov_deg")};
}

void Sky::setTime(const std::string& utc) {
  nlohmann::json d = impl_->document;
  d["time"]["utc"] = utc;
  impl_->commit(std::move(d));
}

void Sky::setLocation(double latitude_deg, double longitude_deg) {
  nlohmann::json d = impl_->document;
  d["location"]["latitude_deg"] = latitude_deg;
  d["location"]["longitude_deg"] = longitude_deg;
  impl_->commit(std::move(d));
}

void Sky::set(const std::string& pointerEqualsValue) {
  nlohmann::json d = impl_->document;
  applyOverride(d, pointerEqualsValue);
  impl_->commit(std::move(d));
}

std::string Sky::get(const std::string& pointer) const {
  const nlohmann::json::json_pointer p(pointer);
  return impl_->document.contains(p) ? impl_->document.at(p).dump() : std::string();
}

SkyFrame Sky::render(int width, int height) {
  if (impl_->context->adopted())
    throw InputError("render(): this sky is embedded in a host's device (Builder::embedded); use record()");
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError("render size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": allowed: 1 to 16384 pixels a side");
  Impl& m = *impl_;
  if (width != m.lastWidth || height != m.lastHeight) m.continueNext = false;
  nlohmann::json d = m.document;
  d["camera"]["width"] = width;
  d["camera"]["height"] = height;
  m.commit(std::move(d));

  SkyRenderOptions options;
  options.continueSequence = m.temporal && m.continueNext;
  const auto start = std::chrono::steady_clock::now();
  RenderResult result = m.renderer.render(m.scene, options);
  SkyFrame frame;
  frame.wallMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame.width = result.image.width;
  frame.height = result.image.height;
  if (result.image.channels == 4) {
    frame.rgba = std::move(result.image.pixels);
  } else {
    frame.rgba.assign(result.image.pixelCount() * 4, 1.0f);
    for (size_t i = 0; i < result.image.pixelCount(); ++i)
      for (int c = 0; c < result.image.channels && c < 3; ++c)
        frame.rgba[i * 4 + c] = result.image.pixels[i * result.image.channels + c];
  }
  frame.gpuMilliseconds = result.frameMilliseconds;
  frame.continued = options.continueSequence;
  frame.cloudsReprojected = result.cloudsReprojected;
  frame.sunZenith_deg = result.view.sunZenith * 180.0 / M_PI;
  frame.sunAzimuth_deg = result.view.sunAzimuth * 180.0 / M_PI;
  m.continueNext = true;
  m.lastWidth = width;
  m.lastHeight = height;
  return frame;
}

void Sky::restartSequence() { impl_->continueNext = false; }

std::string Sky::sceneJson() const { return impl_->document.dump(2) + "\n"; }

std::string Sky::deviceDescription() const { return impl_->context->description(); }

std::vector<std::string> Sky::validationMessages() const { return impl_->context->validationMessages(); }

void saveExr(const SkyFrame& frame, const std::string& path) {
  if (frame.width < 1 || frame.height < 1 || frame.rgba.size() != size_t(frame.width) * size_t(frame.height) * 4)
    throw InputError("saveExr: the frame's pixels (" + std::to_string(frame.rgba.size()) + " floats) are not " +
                     std::to_string(frame.width) + "x" + std::to_string(frame.height) + " RGBA");
  Image image(frame.width, frame.height, 4);
  image.pixels = frame.rgba;
  writeExr(path, image);
}

std::vector<const char*> embeddedDeviceExtensions() { return gpu::requiredDeviceExtensions(); }

void enableEmbeddedDeviceFeatures(VkPhysicalDevice physicalDevice, VkPhysicalDeviceFeatures2& features,
                                  VkPhysicalDeviceVulkan12Features& features12,
                                  VkPhysicalDeviceVulkan13Features& features13) {
  gpu::enableSupportedFeatures(physicalDevice, features, features12, features13);
}

CameraFrame cameraFrame(const SkyCamera& camera) {
  constexpr double kDegree = M_PI / 180.0;
  glm::dvec3 forward, right, up;
  shared::cameraBasis(camera.yaw_deg * kDegree, camera.pitch_deg * kDegree, camera.roll_deg * kDegree, forward, right,
                      up);
  CameraFrame frame{};
  for (int i = 0; i < 3; ++i) {
    frame.forward[i] = forward[i];
    frame.right[i] = right[i];
    frame.up[i] = up[i];
  }
  frame.tanHalfFovX = std::tan(0.5 * camera.fov_deg * kDegree);
  return frame;
}

EmbeddedFrame Sky::record(const EmbeddedTargets& t) {
  Impl& m = *impl_;
  if (!m.context->adopted())
    throw InputError(
        "record(): this sky owns its device; build it with Builder::embedded(...) to record into a host's");
  if (t.width < 1 || t.height < 1 || t.width > 16384 || t.height > 16384)
    throw InputError("embedded targets " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                     ": allowed: 1 to 16384 pixels a side");
  if (t.colourFormat != VK_FORMAT_R16G16B16A16_SFLOAT && t.colourFormat != VK_FORMAT_R32G32B32A32_SFLOAT)
    throw InputError("embedded colour format " + std::to_string(int(t.colourFormat)) +
                     ": allowed: VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT");
  if (!(t.near_m > 0.0) || !(t.far_m > t.near_m))
    throw InputError("embedded depth planes: near " + std::to_string(t.near_m) + " m, far " + std::to_string(t.far_m) +
                     " m: allowed: 0 < near < far");
  if (m.scene.string("/camera/projection") != "perspective")
    throw InputError("embedded mode: /camera/projection is \"" + m.scene.string("/camera/projection") +
                     "\": allowed: \"perspective\" (the host's depth is a perspective projection)");
  if (t.width != m.lastWidth || t.height != m.lastHeight) m.continueNext = false;
  nlohmann::json d = m.document;
  d["camera"]["width"] = t.width;
  d["camera"]["height"] = t.height;
  m.commit(std::move(d));

  SkyRenderOptions options;
  options.continueSequence = m.temporal && m.continueNext;
  EmbeddedRecording targets;
  targets.commands = t.commandBuffer;
  targets.colour = t.colour;
  targets.colourHalf = t.colourFormat == VK_FORMAT_R16G16B16A16_SFLOAT;
  targets.depth = t.depth;
  targets.depthLayout = t.depthLayout;
  targets.near_m = t.near_m;
  targets.far_m = t.far_m;
  targets.reversedDepth = t.depthConvention == DepthConvention::Reversed;
  const uint64_t submissions = m.context->submissionCount();
  const auto start = std::chrono::steady_clock::now();
  RenderResult result = m.renderer.record(m.scene, options, targets);
  EmbeddedFrame frame;
  frame.recordMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame.submittedPreparation = m.context->submissionCount() != submissions;
  for (const gpu::PassTiming& t : result.timings) frame.previousFramePasses.push_back({t.label, t.milliseconds});
  frame.previousFrameGpuMilliseconds = result.frameMilliseconds;
  frame.continued = options.continueSequence;
  frame.cloudsReprojected = result.cloudsReprojected;
  frame.sunZenith_deg = result.view.sunZenith * 180.0 / M_PI;
  frame.sunAzimuth_deg = result.view.sunAzimuth * 180.0 / M_PI;
  m.continueNext = true;
  m.lastWidth = t.width;
  m.lastHeight = t.height;
  return frame;
}

AtmosphereLookups Sky::lookups() const {
  const EmbeddedLookups& l = impl_->renderer.lookups();
  AtmosphereLookups out;
  if (!l.transmittance) throw InputError("lookups(): no frame recorded yet (call record() first)");
  out.transmittance = l.transmittance->view();
  out.aerialPerspective = l.aerialPerspective->view();
  std::memcpy(out.parameters.radii, l.parameters[0], sizeof(out.parameters.radii));
  std::memcpy(out.parameters.sun, l.parameters[1], sizeof(out.parameters.sun));
  std::memcpy(out.parameters.sunIlluminance, l.parameters[2], sizeof(out.parameters.sunIlluminance));
  std::memcpy(out.parameters.image, l.parameters[3], sizeof(out.parameters.image));
  return out;
}

}  // namespace firmament
