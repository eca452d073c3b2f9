// firmament/image.h over core/tonemap.h and core/exr_io.h: the scene's exposure settings kept behind a
// pointer, frames converted to core::Image with their own channel count.
#include "firmament/image.h"

#include "core/exr_io.h"
#include "core/scene.h"
#include "core/tonemap.h"

namespace firmament {
namespace {

// The frame as the renderer's image: RGB when the frame has no clouds, as the renderer returned it.
// `who` prefixes the error for a frame whose pixels do not match its size.
Image toImage(const SkyFrame& frame, const std::string& who = "") {
  if (frame.width < 1 || frame.height < 1 || frame.rgba.size() != size_t(frame.width) * size_t(frame.height) * 4)
    throw InputError(who + "the frame's pixels (" + std::to_string(frame.rgba.size()) + " floats) are not " +
                     std::to_string(frame.width) + "x" + std::to_string(frame.height) + " RGBA");
  const int channels = frame.channels == 3 ? 3 : 4;
  Image image(frame.width, frame.height, channels);
  if (channels == 4) {
    image.pixels = frame.rgba;
  } else {
    for (size_t i = 0; i < image.pixelCount(); ++i)
      for (int c = 0; c < 3; ++c) image.pixels[i * 3 + c] = frame.rgba[i * 4 + c];
  }
  image.metadata = frame.metadata;
  return image;
}

}  // namespace

struct Exposure::Settings {
  ExposureSettings exposure;
};

Exposure::Exposure(std::unique_ptr<Settings> settings) : settings_(std::move(settings)) {}
Exposure::Exposure(const Sky& sky) : Exposure(fromSceneJson(sky.sceneJson())) {}
Exposure Exposure::fromSceneJson(const std::string& sceneJson, const std::string& source) {
  auto s = std::make_unique<Settings>();
  s->exposure = exposureFromScene(Scene::parse(sceneJson, source));
  return Exposure(std::move(s));
}
Exposure::Exposure(const Exposure& other) : settings_(std::make_unique<Settings>(*other.settings_)) {}
Exposure& Exposure::operator=(const Exposure& other) {
  *settings_ = *other.settings_;
  return *this;
}
Exposure::~Exposure() = default;

bool Exposure::automatic() const { return settings_->exposure.mode == ExposureSettings::Mode::Auto; }
void Exposure::setAutomatic(bool automatic) {
  settings_->exposure.mode = automatic ? ExposureSettings::Mode::Auto : ExposureSettings::Mode::Fixed;
}
double Exposure::ev100() const { return settings_->exposure.ev100; }
void Exposure::setEv100(double ev100) { settings_->exposure.ev100 = ev100; }
double Exposure::compensation() const { return settings_->exposure.compensationEv; }
void Exposure::setCompensation(double stops) { settings_->exposure.compensationEv = stops; }
std::string Exposure::toneMap() const { return settings_->exposure.tonemap; }

double Exposure::ev100For(double adapted) const {
  const ExposureSettings& s = settings_->exposure;
  const double base = s.mode == ExposureSettings::Mode::Auto ? autoEv100ForLuminance(adapted, s) : s.ev100;
  return base - s.compensationEv;
}

std::vector<uint8_t> Exposure::toSrgb8(const SkyFrame& frame, double* usedEv100, const double* adapted) const {
  return toneMapToSrgb8(toImage(frame), settings_->exposure, usedEv100, adapted);
}

double Exposure::savePng(const SkyFrame& frame, const std::string& path, const double* adapted) const {
  return writePngPreview(path, toImage(frame), settings_->exposure, adapted);
}

struct EyeAdaptation::State {
  ExposureAdaptation adaptation;
};
EyeAdaptation::EyeAdaptation() : state_(std::make_unique<State>()) {}
EyeAdaptation::~EyeAdaptation() = default;
double EyeAdaptation::update(double logAverage, double dt_s, const Exposure& exposure) {
  return state_->adaptation.update(logAverage, dt_s, exposure.settings_->exposure);
}
bool EyeAdaptation::started() const { return state_->adaptation.started(); }

double logAverageLuminance(const SkyFrame& frame, size_t* nonFinitePixels) {
  return logAverageLuminance(toImage(frame), nonFinitePixels);
}

SkyFrame loadExr(const std::string& path) {
  const Image image = readExr(path);
  SkyFrame frame;
  frame.width = image.width;
  frame.height = image.height;
  frame.channels = image.channels == 4 ? 4 : 3;
  frame.rgba.assign(image.pixelCount() * 4, 1.0f);
  for (size_t i = 0; i < image.pixelCount(); ++i)
    for (int c = 0; c < image.channels && c < 4; ++c)
      frame.rgba[i * 4 + c] = image.pixels[i * size_t(image.channels) + c];
  frame.metadata = image.metadata;
  return frame;
}

void saveExr(const SkyFrame& frame, const std::string& path) { writeExr(path, toImage(frame, "saveExr: ")); }

}  // namespace firmament
