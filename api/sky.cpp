// firmament::Sky (include/firmament/sky.h) over SkyRenderer: the scene as a JSON document that the
// setters edit and Scene::parse validates, one Vulkan context and renderer per sky.
#include "firmament/sky.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include "astro/geodetic.h"
#include "astro/moon.h"
#include "astro/time.h"
#include "clouds/cloud_knobs.h"
#include "clouds/cloud_settings.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/hash.h"
#include "core/scene.h"
#include "firmament/embed.h"
#include "gpu/context.h"
#include "sky/render_plan.h"
#include "sky/scene_weather.h"
#include "sky/sky_renderer.h"

namespace firmament {

struct Sky::Builder::Settings {
  std::optional<std::string> file;
  std::optional<std::string> text;
  std::vector<std::string> overrides;
  std::string device;
  bool temporal = true;
  std::vector<std::string> quality;  // "/path=value" knobs, in order
  int framesInFlight = 1;
  std::optional<gpu::AdoptedDevice> adopted;  // embedded mode
};

namespace {

// ---- quality knobs: paths over SkyRenderOptions ----

struct Knob {
  QualityKnob info;
  // Sets the knob from its JSON value (InputError naming `what` when not allowed) and reads it back.
  void (*set)(SkyRenderOptions&, const nlohmann::json&, const std::string& what);
  nlohmann::json (*get)(const SkyRenderOptions&);
};

[[noreturn]] void notAllowed(const std::string& what, const std::string& allowed) {
  throw InputError("quality " + what + ": allowed: " + allowed);
}

int integerIn(const nlohmann::json& v, int lo, int hi, const std::string& what) {
  if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
    notAllowed(what, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
  return v.get<int>();
}

std::string oneOf(const nlohmann::json& v, std::initializer_list<const char*> names, const std::string& what) {
  std::string allowed;
  for (const char* n : names) {
    if (v.is_string() && v.get<std::string>() == n) return n;
    allowed += (allowed.empty() ? "" : ", ") + std::string(n);
  }
  notAllowed(what, allowed);
}

const std::vector<Knob>& knobTable() {
  static const std::vector<Knob> table = {
      {{"/atmosphere/multiple_scattering", "\"auto\"", "auto, fms, tables",
        "auto: f_ms with the sun up, Bruneton 2017's 4D tables in twilight (blended from -2 to -6 deg; f_ms always "
        "with clouds or terrain); fms: Hillaire 2020's f_ms table and a march; tables: the 4D tables of N orders"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         const std::string name = oneOf(v, {"auto", "fms", "tables"}, w);
         o.multipleScattering = name == "tables" ? MultipleScattering::BrunetonTables
                                : name == "fms"  ? MultipleScattering::HillaireFms
                                                 : MultipleScattering::Auto;
       },
       [](const SkyRenderOptions& o) -> nlohmann::json {
         return o.multipleScattering == MultipleScattering::BrunetonTables ? "tables"
                : o.multipleScattering == MultipleScattering::HillaireFms  ? "fms"
                                                                           : "auto";
       }},
      {{"/atmosphere/scattering_orders", "4", "an integer from 1 to 64",
        "scattering orders of the 4D tables (--multiple-scattering tables)"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.tables.scatteringOrders = integerIn(v, 1, 64, w);
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.tables.scatteringOrders; }},
      {{"/atmosphere/twilight_scattering_orders", "4", "an integer from 1 to 64",
        "scattering orders of the 4D tables the auto form reads in twilight"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.twilightTables.scatteringOrders = integerIn(v, 1, 64, w);
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.twilightTables.scatteringOrders; }},
      {{"/atmosphere/spectral_samples", "\"auto\"", "auto, 3, or a multiple of 3 from 6 to 48",
        "wavelengths: auto (3, or 12 with the sun within 15 deg of the horizon or below), or N integrated to "
        "luminance"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         if (v.is_string() && v.get<std::string>() == "auto") {
           o.luts.spectralSamples = kSpectralSamplesAuto;
           return;
         }
         if (!v.is_number_integer() || v.get<int64_t>() < 3 || v.get<int64_t>() > 48 || v.get<int64_t>() % 3 != 0)
           notAllowed(w, "auto, 3, or a multiple of 3 from 6 to 48");
         o.luts.spectralSamples = v.get<int>();
       },
       [](const SkyRenderOptions& o) -> nlohmann::json {
         if (o.luts.spectralSamples == kSpectralSamplesAuto) return "auto";
         return o.luts.spectralSamples;
       }},
      {{"/atmosphere/sky", "\"lut\"", "lut, march", "the sky-view table read per pixel, or a march per pixel"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.method = oneOf(v, {"lut", "march"}, w) == "march" ? SkyMethod::PerPixel : SkyMethod::SkyViewLut;
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.method == SkyMethod::PerPixel ? "march" : "lut"; }},
      {{"/atmosphere/view_steps", "32", "an integer from 1 to 4096", "march steps per view ray"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.viewSteps = integerIn(v, 1, 4096, w);
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.viewSteps; }},
      {{"/aerial_perspective/columns", "32", "an integer from 2 to 1024",
        "froxel columns of the aerial-perspective volume"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.aerialPerspective.columns = integerIn(v, 2, 1024, w);
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.aerialPerspective.columns; }},
      {{"/aerial_perspective/rows", "32", "an integer from 2 to 1024", "froxel rows of the aerial-perspective volume"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.aerialPerspective.rows = integerIn(v, 2, 1024, w);
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.aerialPerspective.rows; }},
      {{"/aerial_perspective/slices", "32", "an integer from 2 to 1024",
        "depth slices of the aerial-perspective volume"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         o.aerialPerspective.slices = integerIn(v, 2, 1024, w);
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.aerialPerspective.slices; }},
      {{"/aerial_perspective/depth_m", "0", "0 (the clouds' march limit) or a distance in metres up to 1e7",
        "the distance the volume's slices reach"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         if (!v.is_number() || !(v.get<double>() >= 0.0) || v.get<double>() > 1e7)
           notAllowed(w, "0 (the clouds' march limit) or a distance in metres up to 1e7");
         o.aerialPerspective.maxDistance_m = v.get<double>();
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.aerialPerspective.maxDistance_m; }},
      {{"/terrain/lod_footprint", "0.7", "0 (off) or a number from 0.25 to 8",
        "the terrain's level of detail: the field filtered to cells of this many pixel footprints where "
        "that passes its cell (0: the finest samples at every distance)"},
       [](SkyRenderOptions& o, const nlohmann::json& v, const std::string& w) {
         const double x = v.is_number() ? v.get<double>() : -1.0;
         if (!(x == 0.0 || (x >= 0.25 && x <= 8.0))) notAllowed(w, "0 (off) or a number from 0.25 to 8");
         o.terrain.lodFootprint = x;
       },
       [](const SkyRenderOptions& o) -> nlohmann::json { return o.terrain.lodFootprint; }},
  };
  return table;
}

// The cloud march's knobs, "/clouds/march/ID" for each row of the knob table (clouds/cloud_knobs.h,
// docs/clouds/knobs.md): set over the scene's /clouds/quality preset; unset, the preset decides.
const std::string kCloudMarchPrefix = "/clouds/march/";

const CloudKnob* findCloudKnob(const std::string& path) {
  if (path.rfind(kCloudMarchPrefix, 0) != 0) return nullptr;
  const std::string id = path.substr(kCloudMarchPrefix.size());
  std::string ids;
  for (const CloudKnob& k : cloudMarchKnobs()) {
    if (k.id == id) return &k;
    ids += (ids.empty() ? "" : ", ") + k.id;
  }
  throw InputError("quality " + path + ": no such cloud knob; allowed: " + kCloudMarchPrefix + "{" + ids + "}");
}

nlohmann::json knobJson(int v) { return v; }
nlohmann::json knobJson(double v) { return v; }
nlohmann::json knobJson(bool v) { return v; }
nlohmann::json knobJson(AerialPerspective v) { return aerialPerspectiveName(v); }

// The override of the knob with this identifier as JSON; null where none is set.
nlohmann::json cloudOverrideValue(const CloudOverrides& o, const std::string& id) {
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) \
  if (id == cloudKnobIdentifier(#name)) return o.name ? knobJson(*o.name) : nlohmann::json(nullptr);
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
  return nullptr;
}

const Knob& findKnob(const std::string& path) {
  for (const Knob& k : knobTable())
    if (k.info.path == path) return k;
  std::string names;
  for (const Knob& k : knobTable()) names += (names.empty() ? "" : ", ") + k.info.path;
  throw InputError("quality " + path + ": no such knob; allowed: " + names);
}

void applyQuality(SkyRenderOptions& options, const std::string& pathEqualsValue) {
  const size_t eq = pathEqualsValue.find('=');
  if (eq == std::string::npos || eq == 0 || pathEqualsValue[0] != '/')
    throw InputError("quality " + pathEqualsValue + ": allowed: /path=value (e.g. /atmosphere/view_steps=64)");
  const std::string text = pathEqualsValue.substr(eq + 1);
  if (const CloudKnob* cloud = findCloudKnob(pathEqualsValue.substr(0, eq))) {
    try {
      options.clouds.set(cloud->id, text);
    } catch (const InputError& e) {
      throw InputError("quality " + pathEqualsValue + ": " + e.what());
    }
    return;
  }
  const Knob& knob = findKnob(pathEqualsValue.substr(0, eq));
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;  // a bare word: a string
  knob.set(options, value, pathEqualsValue);
}

SkyPlan planOf(const Scene& scene, const SkyRenderOptions& options) {
  const RenderPlan plan = planRender(scene, planOptions(options));
  SkyPlan out;
  out.scene = scene.source();
  out.width = int(scene.integer("/camera/width"));
  out.height = int(scene.integer("/camera/height"));
  for (const PlannedPass& p : plan.passes) out.passes.push_back({p.name, p.output, p.reason, p.perFrame});
  for (const OmittedPass& p : plan.omitted) out.omitted.push_back({p.name, p.reason});
  for (const OmittedPass& p : plan.unavailable) out.unavailable.push_back({p.name, p.reason});
  out.text = describePlan(plan);
  return out;
}

// Where a sky's scene comes from: what a sequence frame is read again from (sequenceScene).
struct SceneSource {
  std::optional<std::string> file, text;
  std::vector<std::string> overrides;
  Scene load(const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> o = overrides;
    o.insert(o.end(), extra.begin(), extra.end());
    return file   ? Scene::load(*file, o)
           : text ? Scene::parse(*text, "<scene json>", o)
                  : Scene::parse(defaultSceneText(), kDefaultSceneName, o);
  }
};

// The scene elapsed_s after `base` with the camera: the source read again with the frame's overrides, so a
// frame depends only on the base scene, its time and its camera.
Scene sequenceScene(const SceneSource& source, const Scene& base, double elapsed_s,
                    const std::optional<SkyCamera>& camera) {
  std::vector<std::string> o;
  if (camera) {
    o.push_back("/camera/yaw_deg=" + roundTripDecimal(camera->yaw_deg));
    o.push_back("/camera/pitch_deg=" + roundTripDecimal(camera->pitch_deg));
    o.push_back("/camera/height_above_ground_m=" + roundTripDecimal(camera->heightAboveGround_m));
    o.push_back("/camera/fov_deg=" + roundTripDecimal(camera->fov_deg));
  }
  if (base.hasSection("clouds"))
    o.push_back("/clouds/time_s=" + roundTripDecimal(base.number("/clouds/time_s") + elapsed_s));
  // The sun follows the clock when the scene takes it from time and location.
  if (!base.hasSection("sun"))
    o.push_back("/time/utc=" +
                astro::formatUtc(astro::addSeconds(astro::parseUtc(base.string("/time/utc")), elapsed_s)));
  // One weather simulation for the whole sequence: it runs from the solar midnight before the first
  // frame (or the scene's own /weather/start_utc) to every frame, so a sequence that crosses a solar
  // midnight runs on through the night instead of starting the day again.
  if (base.hasSection("weather") && !base.at("/weather").contains("start_utc")) {
    const double run_s = sceneWeatherRunSeconds(base) + elapsed_s;
    if (run_s > kSceneWeatherMaxRun_s)
      throw InputError(base.source() + ": a frame " + roundTripDecimal(elapsed_s / 3600.0) + " h after the first is " +
                       roundTripDecimal(run_s / 86400.0) +
                       " days of weather after the solar midnight before the first frame; allowed: at most 7 days");
    o.push_back("/weather/start_utc=" + astro::formatUtc(sceneWeatherStart(base)));
  }
  return source.load(o);
}

}  // namespace

const std::vector<QualityKnob>& qualityKnobs() {
  static const std::vector<QualityKnob> list = [] {
    std::vector<QualityKnob> l;
    for (const Knob& k : knobTable()) l.push_back(k.info);
    for (const CloudKnob& k : cloudMarchKnobs())
      l.push_back(
          {kCloudMarchPrefix + k.id, "null", cloudKnobAllowed(k),
           std::string(k.doc) + " (null: the scene's /clouds/quality preset; its default preset: " + k.value + ")"});
    return l;
  }();
  return list;
}

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
Sky::Builder& Sky::Builder::framesInFlight(int count) {
  if (count < 1 || count > 4) throw InputError("framesInFlight(" + std::to_string(count) + "): allowed: 1 to 4");
  settings_->framesInFlight = count;
  return *this;
}
Sky::Builder& Sky::Builder::quality(const std::string& pathEqualsValue) {
  settings_->quality.push_back(pathEqualsValue);
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
  bool sequence = false;  // setSequenceFrame was called: the frames are a sequence's, never stills
  int lastWidth = 0, lastHeight = 0;
  SkyRenderOptions options;  // the quality knobs
  // Embedded mode's frames in flight: slot 0 is `renderer`, the others are made at their first record();
  // each slot continues its own last frame (the one framesInFlight records before).
  struct Slot {
    std::unique_ptr<SkyRenderer> renderer;  // null for slot 0
    bool continues = false;
    int width = 0, height = 0;
  };
  std::vector<Slot> slots = std::vector<Slot>(1);
  uint64_t recorded = 0;
  size_t lastSlot = 0;
  SkyRenderer& slotRenderer(size_t i) {
    if (i > 0 && !slots[i].renderer) slots[i].renderer = std::make_unique<SkyRenderer>(*context);
    return i == 0 ? renderer : *slots[i].renderer;
  }
  SceneSource source;         // what the scene was built from (sequence frames read it again)
  std::optional<Scene> base;  // the scene as built

  // Validates an edited document and makes it the view; on error the view stays as it was.
  void commit(nlohmann::json edited) {
    scene = Scene::parse(edited.dump(), scene.source());
    document = scene.root();
  }
};

SkyPlan Sky::Builder::explain() const {
  const Settings& s = *settings_;
  const Scene scene = SceneSource{s.file, s.text, s.overrides}.load();
  SkyRenderOptions quality;
  for (const std::string& q : s.quality) applyQuality(quality, q);
  return planOf(scene, quality);
}

std::unique_ptr<Sky> Sky::Builder::build() {
  const Settings& s = *settings_;
  const SceneSource source{s.file, s.text, s.overrides};
  Scene scene = source.load();
  SkyRenderOptions quality;
  for (const std::string& q : s.quality) applyQuality(quality, q);
  gpu::ContextOptions options;
  options.device = s.device;
  if (s.adopted) options.validation = false;  // the host's instance: its own messenger sees the messages
  auto impl = std::make_unique<Impl>(options, s.adopted, scene);
  impl->temporal = s.temporal;
  impl->options = quality;
  impl->slots.resize(size_t(s.framesInFlight));
  impl->source = source;
  impl->base = std::move(scene);
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

void Sky::setQuality(const std::string& pathEqualsValue) {
  SkyRenderOptions o = impl_->options;
  applyQuality(o, pathEqualsValue);
  impl_->options = o;
}

std::string Sky::quality(const std::string& path) const {
  if (const CloudKnob* cloud = findCloudKnob(path)) return cloudOverrideValue(impl_->options.clouds, cloud->id).dump();
  return findKnob(path).get(impl_->options).dump();
}

SkyPlan Sky::plan() const { return planOf(impl_->scene, impl_->options); }

void Sky::setSequenceFrame(double elapsed_s, const SkyCamera& camera) {
  Impl& m = *impl_;
  m.sequence = true;
  m.scene = sequenceScene(m.source, *m.base, elapsed_s, camera);
  m.document = m.scene.root();
}

void Sky::setSequenceFrame(double elapsed_s) {
  Impl& m = *impl_;
  m.sequence = true;
  m.scene = sequenceScene(m.source, *m.base, elapsed_s, std::nullopt);
  m.document = m.scene.root();
}

void Sky::checkSequenceFrame(double elapsed_s, const SkyCamera& camera) const {
  sequenceScene(impl_->source, *impl_->base, elapsed_s, camera);
}

void Sky::checkSequenceFrame(double elapsed_s) const {
  sequenceScene(impl_->source, *impl_->base, elapsed_s, std::nullopt);
}

WeatherSummary Sky::weather() const {
  const Scene& scene = impl_->scene;
  WeatherSummary w;
  if (!scene.hasSection("clouds") || !scene.hasSection("weather")) return w;
  const CloudWeatherMap map = cloudWeatherMapForScene(scene);
  const Image& img = map.map;
  double coverage = 0.0, precipitation = 0.0, top = 0.0;
  size_t cloudy = 0;
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    const float* p = img.pixels.data() + i * size_t(img.channels);
    coverage += p[0];
    cloudy += p[0] > 0.5f;
    precipitation += p[2];
    if (p[0] > 0.0f) top = std::max(top, double(p[3]));
  }
  const double n = double(std::max<size_t>(1, img.pixelCount()));
  w.present = true;
  w.meanCoverage = coverage / n;
  w.cloudyFraction = double(cloudy) / n;
  w.meanPrecipitation_mm_h = precipitation / n;
  w.maxTop_m = top;
  w.startUtc = astro::formatUtc(sceneWeatherStart(scene));
  w.run_h = sceneWeatherRunSeconds(scene) / 3600.0;
  return w;
}

std::string Sky::sceneHash() const { return impl_->scene.hash(); }

std::string canonicalUtc(const std::string& utc) {
  astro::UtcTime t = astro::parseUtc(utc);
  astro::makeAstroTime(t);  // out of the ephemerides' range: InputError
  return astro::formatUtc(t);
}

std::string utcPlusSeconds(const std::string& utc, double seconds) {
  return astro::formatUtc(astro::addSeconds(astro::parseUtc(utc), seconds));
}

double utcSecondsBetween(const std::string& a, const std::string& b) {
  auto days = [](int y, int m, int d) {  // days from civil (Hinnant), proleptic Gregorian
    y -= m <= 2;
    const int era = (y >= 0 ? y : y - 399) / 400;
    const int yoe = y - era * 400;
    const int doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return double(era) * 146097.0 + double(doe);
  };
  auto seconds = [&](const astro::UtcTime& t) {
    return days(t.year, t.month, t.day) * 86400.0 + t.hour * 3600.0 + t.minute * 60.0 + t.second;
  };
  return seconds(astro::parseUtc(b)) - seconds(astro::parseUtc(a));
}

std::string Sky::get(const std::string& pointer) const {
  const nlohmann::json::json_pointer p(pointer);
  return impl_->document.contains(p) ? impl_->document.at(p).dump() : std::string();
}

SkyFrame Sky::render(int width, int height) { return renderFrame(width, height, false); }

SkyFrame Sky::renderStill(int width, int height) {
  restartSequence();
  return renderFrame(width, height, true);
}

SkyFrame Sky::renderFrame(int width, int height, bool still) {
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

  SkyRenderOptions options = m.options;
  options.continueSequence = m.temporal && m.continueNext;
  // A still (the clouds average /clouds/march/still_samples sub-frames): renderStill(), or a Sky without
  // temporal reprojection that makes no sequence frames (`firmament render` without --frames).
  options.still = still || (!m.temporal && !m.sequence);
  const auto start = std::chrono::steady_clock::now();
  RenderResult result = m.renderer.render(m.scene, options);
  SkyFrame frame;
  frame.wallMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame.width = result.image.width;
  frame.height = result.image.height;
  frame.channels = result.image.channels == 4 ? 4 : 3;
  frame.metadata = std::move(result.image.metadata);
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
  frame.sunZenith_deg = result.view.sunZenith * (180.0 / M_PI);
  frame.sunAzimuth_deg = result.view.sunAzimuth * (180.0 / M_PI);
  frame.scene = m.scene.source();
  frame.sceneHash = m.scene.hash();
  {
    const std::string utc = m.scene.string("/time/utc");
    const astro::GeodeticLocation location = astro::GeodeticLocation::fromDegrees(
        m.scene.number("/location/latitude_deg"), m.scene.number("/location/longitude_deg"),
        m.scene.number("/location/height_m"));
    frame.moonAltitude_deg = 90.0 - astro::moonPosition(astro::makeAstroTime(utc), location).zenith * (180.0 / M_PI);
    frame.moonIlluminatedFraction = astro::moonPhase(astro::makeAstroTime(utc)).illuminatedFraction;
  }
  frame.sunSource = result.view.sunSource;
  frame.sunDistance_au = result.view.sunDistanceAu;
  for (const gpu::PassTiming& t : result.timings) frame.passes.push_back({t.label, t.milliseconds});
  frame.precomputeMilliseconds = result.precomputeMilliseconds;
  frame.tablesSource = result.tablesSource;
  frame.spectralSamples = result.spectralSamples;
  frame.timingNote = result.timingNote;
  frame.clouds.rendered = result.clouds.pixelCount() > 0;
  frame.clouds.viewSamplesPerPixel = result.cloudSamples.viewPerPixel;
  frame.clouds.lightSamplesPerPixel = result.cloudSamples.lightPerPixel;
  frame.clouds.noiseSource = result.cloudNoiseSource;
  frame.night.run = result.night.run;
  frame.night.sunAltitude_deg = result.night.sunAltitudeDeg;
  frame.night.moonAltitude_deg = result.night.moonAltitudeDeg;
  frame.night.moonIsTheLight = result.light.moon;
  frame.night.lightReason = result.light.reason;
  frame.night.sunGroundLux = result.light.sunGroundLux;
  frame.night.moonGroundLux = result.light.moonGroundLux;
  m.continueNext = true;
  m.lastWidth = width;
  m.lastHeight = height;
  return frame;
}

void Sky::restartSequence() {
  impl_->continueNext = false;
  for (Impl::Slot& slot : impl_->slots) slot.continues = false;
}

std::string Sky::sceneJson() const { return impl_->document.dump(2) + "\n"; }

std::string Sky::deviceDescription() const { return impl_->context->description(); }

std::vector<std::string> Sky::validationMessages() const { return impl_->context->validationMessages(); }

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
  const size_t slot = size_t(m.recorded % m.slots.size());
  Impl::Slot& s = m.slots[slot];
  if (t.width != s.width || t.height != s.height) s.continues = false;
  nlohmann::json d = m.document;
  d["camera"]["width"] = t.width;
  d["camera"]["height"] = t.height;
  m.commit(std::move(d));

  SkyRenderOptions options = m.options;
  options.continueSequence = m.temporal && s.continues;
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
  RenderResult result = m.slotRenderer(slot).record(m.scene, options, targets);
  EmbeddedFrame frame;
  frame.slot = int(slot);
  frame.recordMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame.submittedPreparation = m.context->submissionCount() != submissions;
  for (const gpu::PassTiming& t : result.timings) frame.previousFramePasses.push_back({t.label, t.milliseconds});
  frame.previousFrameGpuMilliseconds = result.frameMilliseconds;
  frame.continued = options.continueSequence;
  frame.cloudsReprojected = result.cloudsReprojected;
  frame.sunZenith_deg = result.view.sunZenith * (180.0 / M_PI);
  frame.sunAzimuth_deg = result.view.sunAzimuth * (180.0 / M_PI);
  s.continues = true;
  s.width = t.width;
  s.height = t.height;
  m.lastSlot = slot;
  ++m.recorded;
  return frame;
}

AtmosphereLookups Sky::lookups() const {
  const EmbeddedLookups& l = impl_->slotRenderer(impl_->lastSlot).lookups();
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
