// `firmament view [SCENE]`: the interactive viewer (docs/viewer.md). A GLFW window, the sky rendered each
// frame through the public API (include/firmament/sky.h), tone-mapped on the CPU with the scene's
// exposure (include/firmament/image.h), presented with a swapchain of its own (samples/viewer/presenter.h), with
// Dear ImGui controls and a fly camera. --script replays inputs with no person at the window.
// Built only where GLFW and Dear ImGui are found (samples/CMakeLists.txt).
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include "firmament/image.h"
#include "firmament/sky.h"
#include "samples/firmament/command.h"
#include "samples/viewer/fly_camera.h"
#include "samples/viewer/presenter.h"
#include "samples/viewer/script.h"

namespace firmament::cli {
namespace {

using viewer::FlyState;

// A UTC time's fields, from its canonical form "YYYY-MM-DDThh:mm:ss.sssZ" (firmament::canonicalUtc).
struct UtcFields {
  int year = 2000, month = 1, day = 1, hour = 0, minute = 0;
  double second = 0.0;
};
UtcFields utcFields(const std::string& utc) {
  UtcFields t;
  std::sscanf(canonicalUtc(utc).c_str(), "%d-%d-%dT%d:%d:%lfZ", &t.year, &t.month, &t.day, &t.hour, &t.minute,
              &t.second);
  return t;
}

// The median of the values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// FIRMAMENT_VALIDATION set and not "0": the window's device turns the validation layer on too.
bool validationRequested() {
  const char* value = std::getenv("FIRMAMENT_VALIDATION");
  return value && *value && std::strcmp(value, "0") != 0;
}

// What the controls edit besides the camera, read from the sky's scene.
struct Controls {
  UtcFields utc;
  float dayHours = 12.0f;  // UTC hour of day
  int dayOfYear = 172;
  std::vector<float> coverage;  // per cloud layer
  int quality = 1;              // clouds: low, default, high
  int weatherPreset = -1;       // index into kWeatherPresets, -1 without a weather section
  bool autoExposure = true;
  float ev100 = 15.0f;
  float compensation = 0.0f;
  bool reprojection = true;
};

const char* kQualities[] = {"low", "default", "high"};
const char* kWeatherPresets[] = {"clear", "fair-weather", "scattered-showers", "thunderstorm", "overcast", "frontal"};

int dayOfYear(const UtcFields& t) {
  static const int before[] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  const bool leap = (t.year % 4 == 0 && t.year % 100 != 0) || t.year % 400 == 0;
  return before[t.month - 1] + t.day + (leap && t.month > 2 ? 1 : 0);
}

std::string unquote(const std::string& json) {
  return json.size() >= 2 && json.front() == '"' ? json.substr(1, json.size() - 2) : json;
}

class Viewer {
 public:
  Viewer(const Args& args) {
    Sky::Builder builder;
    if (!args.positionals.empty()) builder.sceneFile(args.positionals[0]);
    for (const auto& o : args.all("set")) builder.set(o);
    builder.device(args.getOr("device", ""));
    controls_.reprojection = !args.has("no-reprojection");
    builder.temporalReprojection(true);
    sky_ = builder.build();
    width_ = args.integer("width", 960, 16, 8192);
    height_ = args.integer("height", 540, 16, 8192);
    renderScale_ = float(args.number("render-scale", 1.0));
    if (!(renderScale_ >= 0.05f && renderScale_ <= 1.0f))
      throw InputError("--render-scale " + args.getOr("render-scale", "") + ": allowed: 0.05 to 1");
    if (auto s = args.get("script")) script_ = viewer::loadScript(*s);
    scripted_ = args.has("script");
    readControls();
    readFly();
  }

  // The fly camera from the view: its camera, place and cloud offset (0 without clouds).
  void readFly() {
    fly_.camera = sky_->camera();
    fly_.latitude_deg = std::stod(sky_->get("/location/latitude_deg"));
    fly_.longitude_deg = std::stod(sky_->get("/location/longitude_deg"));
    const std::string east = sky_->get("/clouds/offset_east_m"), north = sky_->get("/clouds/offset_north_m");
    fly_.cloudOffsetEast_m = east.empty() ? 0.0 : std::stod(east);
    fly_.cloudOffsetNorth_m = north.empty() ? 0.0 : std::stod(north);
  }

  int run() {
    if (!glfwInit())
      throw RuntimeError(
          "view: cannot open a window (GLFW could not initialise: is DISPLAY set? "
          "Without a display run it under xvfb-run)");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(width_, height_, "firmament view", nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw RuntimeError("view: GLFW could not create a window");
    }
    int code = kExitOk;
    try {
      code = loop();
    } catch (...) {
      cleanup();
      throw;
    }
    cleanup();
    return code;
  }

 private:
  void cleanup() {
    if (ImGui::GetCurrentContext()) {
      if (presenter_) presenter_->shutdownImGui();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    presenter_.reset();
    if (window_) glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
  }

  void readControls() {
    controls_.utc = utcFields(unquote(sky_->get("/time/utc")));
    controls_.dayHours = float(controls_.utc.hour + controls_.utc.minute / 60.0 + controls_.utc.second / 3600.0);
    controls_.dayOfYear = dayOfYear(controls_.utc);
    controls_.coverage.clear();
    for (int i = 0; i < 8; ++i) {
      const std::string v = sky_->get("/clouds/layers/" + std::to_string(i) + "/coverage");
      if (v.empty()) break;
      controls_.coverage.push_back(std::stof(v));
    }
    const std::string q = unquote(sky_->get("/clouds/quality"));
    for (int i = 0; i < 3; ++i)
      if (q == kQualities[i]) controls_.quality = i;
    const std::string w = unquote(sky_->get("/weather/preset"));
    controls_.weatherPreset = -1;
    for (int i = 0; i < 6; ++i)
      if (w == kWeatherPresets[i]) controls_.weatherPreset = i;
    controls_.autoExposure = unquote(sky_->get("/camera/exposure/mode")) != "fixed";
    controls_.ev100 = std::stof(sky_->get("/camera/exposure/ev100"));
    controls_.compensation = std::stof(sky_->get("/camera/exposure/compensation_ev"));
  }

  // The controls' time: the date's year, the day of the year and the hour (UTC).
  std::string controlsUtc() const {
    char start[32];
    std::snprintf(start, sizeof(start), "%04d-01-01T00:00:00Z", controls_.utc.year);
    return utcPlusSeconds(start, (controls_.dayOfYear - 1) * 86400.0 + controls_.dayHours * 3600.0);
  }

  void applyView() {
    sky_->setCamera(fly_.camera);
    sky_->setLocation(fly_.latitude_deg, fly_.longitude_deg);
    // The clouds pass by: they are placed relative to the location, which the flight moved too.
    if (!sky_->get("/clouds/offset_east_m").empty()) {
      sky_->set("/clouds/offset_east_m=" + std::to_string(fly_.cloudOffsetEast_m));
      sky_->set("/clouds/offset_north_m=" + std::to_string(fly_.cloudOffsetNorth_m));
    }
  }

  void advanceTime(double hours) {
    sky_->setTime(utcPlusSeconds(unquote(sky_->get("/time/utc")), hours * 3600));
    readControls();
  }

  Exposure exposure() const {
    Exposure e(*sky_);
    e.setAutomatic(controls_.autoExposure);
    e.setEv100(controls_.ev100);
    e.setCompensation(controls_.compensation);
    return e;
  }

  // The frame as the viewer shows and saves it: RGBA (A 1 without clouds), the viewer's own metadata.
  SkyFrame shown(SkyFrame f) const {
    f.channels = 4;
    f.metadata = {{"firmament.device", sky_->deviceDescription()}, {"firmament.source", "firmament view"}};
    return f;
  }

  // A still of the view (every pixel marched, as `firmament render` of the saved view renders it):
  // OUT.exr, OUT.png with the viewer's exposure, and the view as OUT.view.json, each written atomically.
  void screenshot(const std::filesystem::path& out) {
    const SkyFrame f = shown(sky_->renderStill(renderWidth(), renderHeight()));
    saveExr(f, out.string());
    const double ev = exposure().savePng(f, std::filesystem::path(out).replace_extension(".png").string(),
                                         controls_.autoExposure ? &adaptedLuminance_ : nullptr);
    writeTextAtomically(std::filesystem::path(out).replace_extension(".view.json"), sky_->sceneJson());
    char line[300];
    std::snprintf(line, sizeof(line), "screenshot %s (+ .png, EV100 %.2f; + .view.json): %dx%d, %.1f ms", out.c_str(),
                  ev, f.width, f.height, f.gpuMilliseconds);
    info(line);
    frame_ = f;
  }

  void save(const std::filesystem::path& out) {
    writeTextAtomically(out, sky_->sceneJson());
    info("saved the view as " + out.string() + " (firmament render " + out.string() + " reproduces it)");
  }

  int renderWidth() const { return std::max(1, int(std::lround(framebufferWidth_ * renderScale_))); }
  int renderHeight() const { return std::max(1, int(std::lround(framebufferHeight_ * renderScale_))); }

  // One scripted command; false when the script ends the viewer.
  bool runScriptCommand() {
    if (waitFrames_ > 0) {
      --waitFrames_;
      return true;
    }
    if (next_ >= script_.size()) return false;
    const viewer::ScriptCommand& c = script_[next_++];
    using K = viewer::ScriptCommand::Kind;
    switch (c.kind) {
      case K::Key:
        viewer::fly(fly_, viewer::parseKeys(c.text), c.a);
        break;
      case K::Drag:
        viewer::drag(fly_, c.a, c.b);
        break;
      case K::Speed:
        fly_.speed_m_s = c.a;
        break;
      case K::Advance:
        advanceTime(c.a);
        break;
      case K::Set:
        sky_->set(c.text);
        readControls();
        readFly();
        break;
      case K::Wait:
        waitFrames_ = int(c.a) - 1;
        break;
      case K::Screenshot:
        applyView();
        screenshot(c.text);
        break;
      case K::Save:
        applyView();
        save(c.text);
        break;
      case K::Quit:
        return false;
    }
    return true;
  }

  void interactiveInput(double seconds) {
    ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
      viewer::FlyInput in;
      auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1 : 0; };
      in.forward = down(GLFW_KEY_W) - down(GLFW_KEY_S);
      in.right = down(GLFW_KEY_D) - down(GLFW_KEY_A);
      in.up = down(GLFW_KEY_E) - down(GLFW_KEY_Q);
      const double boost = down(GLFW_KEY_LEFT_SHIFT) ? 10.0 : 1.0;
      fly_.speed_m_s *= boost;
      viewer::fly(fly_, in, std::min(seconds, 0.5));
      fly_.speed_m_s /= boost;
    }
    double x = 0, y = 0;
    glfwGetCursorPos(window_, &x, &y);
    const bool pressed = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                         glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (pressed && dragging_) viewer::drag(fly_, x - lastX_, y - lastY_);
    dragging_ = pressed && (dragging_ || !io.WantCaptureMouse);
    lastX_ = x;
    lastY_ = y;
  }

  void panel() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("firmament");
    ImGui::Text("frame %.1f ms (GPU %.1f ms)%s", frameWallMs_, frame_.gpuMilliseconds,
                frame_.cloudsReprojected ? ", clouds reprojected" : "");
    ImGui::Text("%dx%d, sun zenith %.1f deg", frame_.width, frame_.height, frame_.sunZenith_deg);
    bool timeChanged = ImGui::SliderFloat("hour (UTC)", &controls_.dayHours, 0.0f, 23.99f, "%.2f");
    timeChanged |= ImGui::SliderInt("day of year", &controls_.dayOfYear, 1, 365);
    if (timeChanged) sky_->setTime(controlsUtc());
    float lat = float(fly_.latitude_deg), lon = float(fly_.longitude_deg);
    if (ImGui::SliderFloat("latitude", &lat, -89.9f, 89.9f, "%.3f")) fly_.latitude_deg = lat;
    if (ImGui::SliderFloat("longitude", &lon, -180.0f, 180.0f, "%.3f")) fly_.longitude_deg = lon;
    float height = float(fly_.camera.heightAboveGround_m);
    if (ImGui::SliderFloat("height (m)", &height, float(viewer::kMinHeight_m), 1e7f, "%.1f",
                           ImGuiSliderFlags_Logarithmic))
      fly_.camera.heightAboveGround_m = height;
    float speed = float(fly_.speed_m_s);
    if (ImGui::SliderFloat("speed (m/s)", &speed, float(viewer::kMinSpeed_m_s), float(viewer::kMaxSpeed_m_s), "%.1f",
                           ImGuiSliderFlags_Logarithmic))
      fly_.speed_m_s = speed;
    for (size_t i = 0; i < controls_.coverage.size(); ++i) {
      const std::string label = "coverage, layer " + std::to_string(i);
      if (ImGui::SliderFloat(label.c_str(), &controls_.coverage[i], 0.0f, 1.0f))
        sky_->set("/clouds/layers/" + std::to_string(i) + "/coverage=" + std::to_string(controls_.coverage[i]));
    }
    if (!controls_.coverage.empty() && ImGui::Combo("cloud quality", &controls_.quality, kQualities, 3))
      sky_->set(std::string("/clouds/quality=\"") + kQualities[controls_.quality] + "\"");
    if (controls_.weatherPreset >= 0 && ImGui::Combo("weather", &controls_.weatherPreset, kWeatherPresets, 6))
      sky_->set(std::string("/weather/preset=\"") + kWeatherPresets[controls_.weatherPreset] + "\"");
    ImGui::Checkbox("auto exposure", &controls_.autoExposure);
    if (!controls_.autoExposure) ImGui::SliderFloat("EV100", &controls_.ev100, -10.0f, 24.0f, "%.1f");
    ImGui::SliderFloat("compensation (EV)", &controls_.compensation, -5.0f, 5.0f, "%.1f");
    if (ImGui::Checkbox("temporal reprojection", &controls_.reprojection)) sky_->restartSequence();
    if (ImGui::Button("screenshot")) {
      applyView();
      screenshot(nextPath("firmament-view", ".exr"));
    }
    ImGui::SameLine();
    if (ImGui::Button("save view")) {
      applyView();
      save(nextPath("firmament-view", ".json"));
    }
    ImGui::TextDisabled("WASD move, Q/E down/up, drag to turn, shift x10");
    ImGui::End();
  }

  // OUT-NNN.ext in the current folder, the first that does not exist yet.
  static std::filesystem::path nextPath(const std::string& stem, const std::string& extension) {
    for (int i = 1;; ++i) {
      char name[64];
      std::snprintf(name, sizeof(name), "%s-%03d%s", stem.c_str(), i, extension.c_str());
      if (!std::filesystem::exists(name)) return name;
    }
  }

  int loop() {
    presenter_ = std::make_unique<viewer::Presenter>(window_, validationRequested());
    info("view: renderer on " + sky_->deviceDescription() + "; window on " + presenter_->deviceName());
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // writes no imgui.ini
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window_, true);
    presenter_->initImGui();

    std::vector<double> wallMs, gpuMs;
    auto last = std::chrono::steady_clock::now();
    while (!glfwWindowShouldClose(window_)) {
      glfwPollEvents();
      glfwGetFramebufferSize(window_, &framebufferWidth_, &framebufferHeight_);
      if (framebufferWidth_ == 0 || framebufferHeight_ == 0) {
        glfwWaitEvents();
        continue;
      }
      const auto now = std::chrono::steady_clock::now();
      const double seconds = std::chrono::duration<double>(now - last).count();
      last = now;
      ImGui_ImplVulkan_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      if (scripted_) {
        if (!runScriptCommand()) break;
      } else {
        interactiveInput(seconds);
      }
      panel();
      ImGui::Render();
      applyView();
      if (!controls_.reprojection) sky_->restartSequence();
      const auto start = std::chrono::steady_clock::now();
      frame_ = shown(sky_->render(renderWidth(), renderHeight()));
      const Exposure e = exposure();
      if (e.automatic()) adaptedLuminance_ = adaptation_.update(logAverageLuminance(frame_), seconds, e);
      std::vector<uint8_t> srgb = e.toSrgb8(frame_, nullptr, e.automatic() ? &adaptedLuminance_ : nullptr);
      const size_t pixels = size_t(frame_.width) * size_t(frame_.height);
      std::vector<uint8_t> rgba(pixels * 4, 255);
      const int channels = int(srgb.size() / pixels);
      for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = srgb[i * channels + c];
      presenter_->present(rgba.data(), frame_.width, frame_.height, ImGui::GetDrawData());
      frameWallMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      wallMs.push_back(frameWallMs_);
      gpuMs.push_back(frame_.gpuMilliseconds);
    }
    if (!wallMs.empty()) {
      // The first frame computes the tables and compiles pipelines: the medians leave it out.
      const size_t skip = wallMs.size() > 1 ? 1 : 0;
      char line[300];
      std::snprintf(line, sizeof(line),
                    "view: %zu frames at %dx%d; after the first, median frame %.1f ms (render + tone map + present), "
                    "median GPU %.1f ms",
                    wallMs.size(), renderWidth(), renderHeight(),
                    median(std::vector<double>(wallMs.begin() + skip, wallMs.end())),
                    median(std::vector<double>(gpuMs.begin() + skip, gpuMs.end())));
      info(line);
    }
    std::vector<std::string> messages = sky_->validationMessages();
    for (const auto& m : presenter_->validationMessages()) messages.push_back(m);
    for (const auto& m : messages) warn("validation: " + m);
    if (!messages.empty()) {
      warn("view: " + std::to_string(messages.size()) + " validation messages");
      return kExitRuntime;
    }
    return kExitOk;
  }

  std::unique_ptr<Sky> sky_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<viewer::Presenter> presenter_;
  FlyState fly_;
  Controls controls_;
  SkyFrame frame_;
  EyeAdaptation adaptation_;
  double adaptedLuminance_ = 0.0;
  double frameWallMs_ = 0.0;
  int width_ = 960, height_ = 540;
  int framebufferWidth_ = 0, framebufferHeight_ = 0;
  float renderScale_ = 1.0f;
  bool scripted_ = false;
  std::vector<viewer::ScriptCommand> script_;
  size_t next_ = 0;
  int waitFrames_ = 0;
  bool dragging_ = false;
  double lastX_ = 0, lastY_ = 0;
};

int runView(const Args& args) {
  Viewer viewer(args);
  return viewer.run();
}

const CommandRegistration reg{
    {"view",
     "interactive viewer: fly through the sky (GLFW window, Dear ImGui controls)",
     "view [SCENE] [--width W --height H] [--render-scale F] [--set /PATH=VALUE]... [--script FILE] "
     "[--no-reprojection] [--device D]",
     {{"width", "W", "window width (default 960)"},
      {"height", "H", "window height (default 540)"},
      {"render-scale", "F", "render at this fraction of the window's size, blit scaled (0.05 to 1, default 1)"},
      setOption(),
      {"script", "FILE", "replay the inputs in FILE (one command a line, docs/viewer.md) and quit at its end"},
      {"no-reprojection", "", "render every frame as a still (no temporal reprojection of the clouds)"},
      deviceOption()},
     0,
     1,
     runView}};

}  // namespace
}  // namespace firmament::cli
