// firmament::Sky (include/firmament/sky.h) over SkyRenderer: the scene as a JSON document that the
// setters edit and Scene::parse validates, one Vulkan context and renderer per sky.
#include "firmament/sky.h"

#include <chrono>
#include <cmath>
#include <optional>

#include "core/error.h"
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
Sky::Builder& Sky::Builder::temporalReprojection(bool enabled) {
  settings_->temporal = enabled;
  return *this;
}

struct Sky::Impl {
  explicit Impl(const gpu::ContextOptions& options, Scene initial)
      : context(options), renderer(context), scene(std::move(initial)), document(scene.root()) {}
  gpu::Context context;
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
  auto impl = std::make_unique<Impl>(options, std::move(scene));
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

std::string Sky::deviceDescription() const { return impl_->context.description(); }

std::vector<std::string> Sky::validationMessages() const { return impl_->context.validationMessages(); }

}  // namespace firmament
