#include "eval/atmosphere_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "core/color.h"
#include "core/error.h"
#include "core/image_metrics.h"
#include "core/log.h"
#include "core/statistics.h"
#include "eval/gpu_warm_up.h"
#include "eval/reference_image_cache.h"
#include "eval/scenarios.h"
#include "sky/scene_view.h"

namespace firmament {
namespace {

// Index of the median element (the lower one for an even count), to report that run's passes.
size_t medianIndex(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  return order.empty() ? 0 : order[(order.size() - 1) / 2];
}

std::string sizeLabel(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// The values of a knob that a quick run measures: its quickValues, else the first (cheapest) and
// the default.
std::vector<BenchKnobValue> quickValues(const BenchKnob& knob) {
  std::vector<BenchKnobValue> out;
  for (size_t i = 0; i < knob.values.size(); ++i) {
    const std::string& v = knob.values[i].value;
    const bool keep = knob.quickValues.empty()
                          ? i == 0 || v == knob.defaultValue
                          : std::find(knob.quickValues.begin(), knob.quickValues.end(), v) != knob.quickValues.end();
    if (keep) out.push_back(knob.values[i]);
  }
  return out;
}

struct TableTiming {
  double precomputeMs = 0.0;
  std::vector<gpu::PassTiming> passes;    // of the median run
  std::unique_ptr<SkyRenderer> renderer;  // the last one, its tables current
};

// Tables: fresh renderers (nothing cached in memory; the context has no disk cache), the median of
// their table time over `repeats` (once when one takes over kSinglePrecomputeMilliseconds).
// On a GPU the tables are timed after warmUpGpu. On the H100 the defaults' tables then measured
// 2.5 ms, against 14.1 ms before, but another row of the same work still measured 8 ms: each repeat
// builds a fresh renderer first (docs/gpu.md "Checking on a real GPU").
TableTiming measureTables(gpu::Context& context, const Scene& scene, const SkyRenderOptions& options, int repeats) {
  TableTiming t;
  std::vector<double> ms;
  std::vector<std::vector<gpu::PassTiming>> passes;
  SkyRenderOptions onGpu = options;  // the images are not needed, only the tables' time
  onGpu.downloadImages = false;
  if (!context.isCpu()) {  // no renderer to build on lavapipe
    SkyRenderer warm(context);
    warmUpGpu(warm, scene, onGpu);
  }
  for (int i = 0; i < repeats; ++i) {
    t.renderer = std::make_unique<SkyRenderer>(context);
    RenderResult r = t.renderer->render(scene, onGpu);
    if (r.tablesSource != "computed")
      throw RuntimeError("bench: the tables came from the " + r.tablesSource +
                         "; the bench needs a context without a disk cache");
    ms.push_back(r.precomputeMilliseconds);
    passes.push_back({});
    for (const auto& p : r.timings)
      if (p.label.rfind("atmosphere/", 0) == 0) passes.back().push_back(p);
    if (r.precomputeMilliseconds > kSinglePrecomputeMilliseconds) break;
  }
  t.precomputeMs = median(ms);
  t.passes = passes[medianIndex(ms)];
  return t;
}

struct FrameTiming {
  double frameMs = 0.0;
  Image image;
  std::string timingNote;
};

// Frame: one warm-up render (tables from memory when the atmosphere is unchanged), then `repeats`
// renders; the median of their per-frame GPU time.
FrameTiming measureFrames(SkyRenderer& renderer, const Scene& scene, const SkyRenderOptions& options, int repeats) {
  FrameTiming f;
  renderer.render(scene, options);
  SkyRenderOptions onGpu = options;  // no download but the last: a GPU stays busy (downloadImages)
  onGpu.downloadImages = false;
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i) {
    RenderResult r = renderer.render(scene, i + 1 == repeats ? options : onGpu);
    ms.push_back(r.frameMilliseconds);
    f.timingNote = r.timingNote;
    if (i + 1 == repeats) f.image = std::move(r.image);
  }
  f.frameMs = median(ms);
  return f;
}

BenchReference describeReference(const BenchScenario& scenario, const CachedReference& cached, int spp,
                                 int wavelengths) {
  BenchReference r;
  r.scenario = scenario.name;
  r.width = cached.image.width;
  r.height = cached.image.height;
  r.samplesPerPixel = spp;
  r.wavelengths = wavelengths;
  r.seconds = cached.seconds;
  r.fromCache = cached.fromCache;
  r.file = cached.file;
  r.medianRelativeNoise = cached.medianRelativeNoise;
  r.p95RelativeNoise = cached.p95RelativeNoise;
  double sumNoise = 0.0, sumY2 = 0.0;
  const Image& image = cached.image;
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const float* p = image.pixels.data() + i * 4;
    const double y = luminanceRec709(p), se = p[3];
    sumNoise += se * se;
    sumY2 += y * y;
    r.peakLuminance = std::max(r.peakLuminance, y);
  }
  const double n = double(std::max<size_t>(image.pixelCount(), 1));
  r.meanSquaredNoise = sumNoise / n;
  r.meanSquaredLuminance = sumY2 / n;
  r.noiseRelRmse = r.meanSquaredLuminance > 0 ? std::sqrt(r.meanSquaredNoise / r.meanSquaredLuminance) : 0.0;
  r.noisePsnrDb =
      r.meanSquaredNoise > 0 ? 10.0 * std::log10(r.peakLuminance * r.peakLuminance / r.meanSquaredNoise) : INFINITY;
  return r;
}

}  // namespace

Scene benchScenarioScene(const BenchScenario& scenario) {
  std::vector<std::string> overrides = scenario.overrides;
  overrides.push_back("/camera/width=" + std::to_string(scenario.width));
  overrides.push_back("/camera/height=" + std::to_string(scenario.height));
  return evalScenarioScene("atmosphere", scenario.name, overrides);
}

std::vector<BenchScenario> atmosphereBenchScenarios(bool quick) {
  // The scene files (eval/scenarios/atmosphere/*.json) keep the sun disc out of the frame (its pixels
  // would be the PSNR peak and dominate every error), but the bright sky around it in: the sun is 45-60
  // degrees to the side of the view. Twilight is multiple scattering almost only, the reference's
  // noisiest case: fewer pixels, more paths (its index entry).
  const nlohmann::json index = evalScenarioIndex("atmosphere");
  std::vector<BenchScenario> s;
  for (const nlohmann::json& e : index.at("scenarios")) {
    BenchScenario scenario;
    scenario.name = e.at("name").get<std::string>();
    scenario.description = e.at("description").get<std::string>();
    const nlohmann::json& sized = quick ? e.at("quick") : e;
    const Scene scene = evalScenarioScene("atmosphere", scenario.name);
    scenario.width = quick ? sized.at("width").get<int>() : int(scene.integer("/camera/width"));
    scenario.height = quick ? sized.at("height").get<int>() : int(scene.integer("/camera/height"));
    scenario.referenceSamples = sized.at("reference_samples").get<int>();
    s.push_back(scenario);
  }
  return s;
}

std::vector<BenchKnob> atmosphereBenchKnobs(bool quick) {
  std::vector<BenchKnob> knobs;
  auto add = [&](std::string name, std::string description, std::string defaultValue,
                 std::vector<BenchKnobValue> values, bool tables = false) {
    knobs.push_back({std::move(name), std::move(description), std::move(defaultValue), std::move(values), tables});
  };
  auto ints = [](std::vector<int> values, std::function<void(SkyRenderOptions&, int)> set) {
    std::vector<BenchKnobValue> out;
    for (int v : values) out.push_back({std::to_string(v), [v, set](SkyRenderOptions& o) { set(o, v); }});
    return out;
  };
  auto sizes = [](std::vector<std::pair<int, int>> values, std::function<void(SkyRenderOptions&, int, int)> set) {
    std::vector<BenchKnobValue> out;
    for (auto [w, h] : values) out.push_back({sizeLabel(w, h), [w, h, set](SkyRenderOptions& o) { set(o, w, h); }});
    return out;
  };
  const SkyRenderOptions d;
  add("transmittance_size", "transmittance table T(r, mu), width (mu) x height (r)",
      sizeLabel(d.luts.transmittanceWidth, d.luts.transmittanceHeight),
      sizes({{32, 8}, {64, 16}, {128, 32}, {256, 64}, {512, 128}},
            [](SkyRenderOptions& o, int w, int h) { o.luts.transmittanceWidth = w, o.luts.transmittanceHeight = h; }),
      true);
  add("transmittance_steps", "trapezoid intervals of each transmittance texel's optical depth",
      std::to_string(d.luts.transmittanceSteps),
      ints({5, 10, 25, 50, 100, 200}, [](SkyRenderOptions& o, int v) { o.luts.transmittanceSteps = v; }), true);
  add("ms_size", "multiple-scattering table Psi_ms(r, mu_s), N x N", std::to_string(d.luts.multipleScatteringSize),
      ints({4, 8, 16, 32, 64}, [](SkyRenderOptions& o, int v) { o.luts.multipleScatteringSize = v; }), true);
  add("ms_theta_samples", "directions of the multiple-scattering integral: zenith bands over the sphere",
      std::to_string(d.luts.multipleScatteringThetaSamples),
      ints({4, 8, 16, 32, 64}, [](SkyRenderOptions& o, int v) { o.luts.multipleScatteringThetaSamples = v; }), true);
  add("ms_orders",
      "multiple-scattering orders iterated before the geometric tail; 1 = Hillaire 2020 (isotropic, f_ms series)",
      std::to_string(d.luts.multipleScatteringOrders),
      ints({1, 2, 3, 4, 6}, [](SkyRenderOptions& o, int v) { o.luts.multipleScatteringOrders = v; }), true);
  add("ms_phi_samples", "directions of the multiple-scattering integral: azimuth samples per zenith band",
      std::to_string(d.luts.multipleScatteringPhiSamples),
      ints({1, 2, 4, 8}, [](SkyRenderOptions& o, int v) { o.luts.multipleScatteringPhiSamples = v; }), true);
  add("ms_steps", "march steps per direction of the multiple-scattering table",
      std::to_string(d.luts.multipleScatteringSteps),
      ints({5, 10, 20, 40}, [](SkyRenderOptions& o, int v) { o.luts.multipleScatteringSteps = v; }), true);
  add("view_steps", "march steps along each view ray (per sky-view texel, or per pixel)", std::to_string(d.viewSteps),
      ints({4, 8, 16, 32, 64, 128}, [](SkyRenderOptions& o, int v) { o.viewSteps = v; }));
  add("sky_view_size", "sky-view table, azimuth x zenith samples", sizeLabel(d.skyViewWidth, d.skyViewHeight),
      sizes({{48, 27}, {96, 54}, {192, 108}, {384, 216}},
            [](SkyRenderOptions& o, int w, int h) { o.skyViewWidth = w, o.skyViewHeight = h; }));
  add("method", "lut: sky-view table per frame (Hillaire 2020); per-pixel: march every pixel",
      d.method == SkyMethod::SkyViewLut ? "lut" : "per-pixel",
      {{"lut", [](SkyRenderOptions& o) { o.method = SkyMethod::SkyViewLut; }},
       {"per-pixel", [](SkyRenderOptions& o) { o.method = SkyMethod::PerPixel; }}});
  add("spectral_samples",
      "wavelengths: 3 (Bruneton's conversion to Rec.709) or N over 360-830 nm integrated to luminance",
      d.luts.spectralSamples == kSpectralSamplesAuto ? std::string("auto") : std::to_string(d.luts.spectralSamples),
      ints({3, 6, 12, 24, 48}, [](SkyRenderOptions& o, int v) { o.luts.spectralSamples = v; }), true);
  knobs.back().quickValues = {"3", "12"};  // the two that the default (auto) chooses between
  add("fms_sky_irradiance_size", "f_ms form: the ground's skylight table, mu_s x r",
      sizeLabel(d.fmsSkyIrradiance.width, d.fmsSkyIrradiance.height),
      sizes({{16, 4}, {32, 8}, {64, 16}, {128, 32}},
            [](SkyRenderOptions& o, int w, int h) { o.fmsSkyIrradiance.width = w, o.fmsSkyIrradiance.height = h; }),
      true);
  add("fms_sky_irradiance_theta", "f_ms form: the ground's skylight, theta x 2 theta directions over the hemisphere",
      std::to_string(d.fmsSkyIrradiance.thetaSamples),
      ints({2, 4, 8, 16}, [](SkyRenderOptions& o, int v) { o.fmsSkyIrradiance.thetaSamples = v; }), true);
  add("fms_sky_irradiance_steps", "f_ms form: the ground's skylight, march steps per direction",
      std::to_string(d.fmsSkyIrradiance.marchSteps),
      ints({4, 8, 16, 32}, [](SkyRenderOptions& o, int v) { o.fmsSkyIrradiance.marchSteps = v; }), true);
  const char* kShippedMode = d.multipleScattering == MultipleScattering::HillaireFms      ? "f_ms"
                             : d.multipleScattering == MultipleScattering::BrunetonTables ? "tables"
                                                                                          : "auto";
  add("multiple_scattering",
      "auto: f_ms with the sun above -2 deg, the 4D tables below -6 deg, blended between; f_ms: Hillaire 2020's "
      "Psi_ms (all orders, isotropic); tables: Bruneton 2017's 4D tables",
      kShippedMode,
      {{"auto", [](SkyRenderOptions& o) { o.multipleScattering = MultipleScattering::Auto; }},
       {"f_ms", [](SkyRenderOptions& o) { o.multipleScattering = MultipleScattering::HillaireFms; }},
       {"tables", [](SkyRenderOptions& o) { o.multipleScattering = MultipleScattering::BrunetonTables; }}},
      true);
  // The tables form's own knobs switch the form on (the shipped form is f_ms): their default marks
  // the tables' default setting.
  auto tablesForm = [](std::vector<BenchKnobValue> values) {
    for (auto& v : values)
      v.apply = [inner = v.apply](SkyRenderOptions& o) {
        o.multipleScattering = MultipleScattering::BrunetonTables;
        inner(o);
      };
    return values;
  };
  add("scattering_orders", "tables form: scattering orders N (single scattering plus N - 1)",
      std::to_string(d.tables.scatteringOrders),
      tablesForm(ints({1, 2, 3, 4, 6}, [](SkyRenderOptions& o, int v) { o.tables.scatteringOrders = v; })), true);
  knobs.back().quickValues = {"1", "2"};
  add("tables_integration_steps", "tables form: trapezoid intervals along each ray of the 4D tables",
      std::to_string(d.tables.integrationSteps),
      tablesForm(ints({25, 50, 100}, [](SkyRenderOptions& o, int v) { o.tables.integrationSteps = v; })), true);
  knobs.back().quickValues = {};
  // Not swept: the 4D tables' sizes (nu, mu_s, mu, r), their irradiance table and direction counts
  // (docs/atmosphere-tables.md measures them); add entries here like the ones above.
  if (quick) {
    for (auto& k : knobs) {
      if (k.name == "tables_integration_steps")
        k.values.clear();  // ~20 s per table computation
      else if (k.name != "method" && k.name != "multiple_scattering")
        k.values = quickValues(k);
    }
  }
  knobs.erase(std::remove_if(knobs.begin(), knobs.end(), [](const BenchKnob& k) { return k.values.empty(); }),
              knobs.end());
  return knobs;
}

double maxRelativeLuminanceError(const Image& test, const Image& reference) {
  double worst = 0.0;
  for (float e : relativeLuminanceError(test, reference))
    if (std::isfinite(e)) worst = std::max(worst, double(e));
  return worst;
}

AtmosphereBenchResult runAtmosphereBench(gpu::Context& context, const AtmosphereBenchConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  AtmosphereBenchResult result;
  result.device = context.description();
  const int repeats = std::max(1, config.repeats);

  std::vector<Scene> scenes;
  std::vector<Image> references;
  for (const auto& scenario : config.scenarios) {
    scenes.push_back(benchScenarioScene(scenario));
    ReferenceQuality quality = config.referenceQuality;
    quality.samplesPerPixel = scenario.referenceSamples;
    CachedReference cached = cachedReferenceImage(scenes.back(), quality, config.outDir / "references", scenario.name);
    result.references.push_back(describeReference(scenario, cached, quality.samplesPerPixel, quality.wavelengthCount));
    references.push_back(std::move(cached.image));
  }

  // Warm-up: the first dispatch of each pipeline compiles it (lavapipe: ~0.2 s).
  if (!scenes.empty()) {
    SkyRenderer warm(context);
    for (SkyMethod method : {SkyMethod::SkyViewLut, SkyMethod::PerPixel}) {
      SkyRenderOptions o = config.defaults;
      o.method = method;
      warm.render(scenes.front(), o);
    }
  }

  struct Run {
    std::string knob, value;
    SkyRenderOptions options;
  };
  std::vector<Run> runs{{"default", "default", config.defaults}};
  for (const auto& knob : config.knobs)
    for (const auto& v : knob.values) {
      Run run{knob.name, v.value, config.defaults};
      v.apply(run.options);
      runs.push_back(std::move(run));
    }

  // The tables depend on the atmosphere only: they are timed on the first scenario and reused (from
  // the renderer's memory) by every scenario with the same atmosphere; another atmosphere is timed
  // on its own.
  std::vector<std::string> atmosphereKeys;
  for (const Scene& scene : scenes) atmosphereKeys.push_back(makeSceneView(scene).atmosphere.hash());
  {
    Progress progress("bench atmosphere", uint64_t(runs.size() * config.scenarios.size()));
    for (const auto& run : runs) {
      std::map<std::string, TableTiming> tables;  // by atmosphere key
      for (size_t s = 0; s < config.scenarios.size(); ++s) {
        auto it = tables.find(atmosphereKeys[s]);
        if (it == tables.end())
          it = tables.emplace(atmosphereKeys[s], measureTables(context, scenes[s], run.options, repeats)).first;
        TableTiming& t = it->second;
        FrameTiming f = measureFrames(*t.renderer, scenes[s], run.options, repeats);
        ImageMetrics metrics = compareImages(f.image, references[s]);
        BenchRow row;
        row.knob = run.knob;
        row.value = run.value;
        row.scenario = config.scenarios[s].name;
        row.precomputeMs = t.precomputeMs;
        row.frameMs = f.frameMs;
        row.relRmse = metrics.luminance.relativeRmse;
        row.psnrDb = metrics.psnrDb;
        row.maxRelErr = maxRelativeLuminanceError(f.image, references[s]);
        row.device = result.device;
        result.rows.push_back(row);
        if (run.knob == "default" && s == 0) result.defaultTablePasses = t.passes;
        if (!f.timingNote.empty()) result.timingNote = f.timingNote;
        progress.advance();
      }
    }
  }

  if (config.fullFrameTiming && !config.scenarios.empty()) {
    BenchScenario big = config.scenarios.front();
    big.width = config.fullFrameWidth;
    big.height = config.fullFrameHeight;
    const Scene scene = benchScenarioScene(big);
    Progress progress("bench atmosphere 1280x720", 2 * uint64_t(repeats + 1));
    for (SkyMethod method : {SkyMethod::SkyViewLut, SkyMethod::PerPixel}) {
      SkyRenderOptions o = config.defaults;
      o.method = method;
      SkyRenderer renderer(context);
      renderer.render(scene, o);  // tables and warm-up
      progress.advance();
      o.downloadImages = false;  // a GPU stays busy between the timed frames
      std::vector<double> ms;
      std::vector<std::vector<gpu::PassTiming>> passes;
      for (int i = 0; i < repeats; ++i) {
        RenderResult r = renderer.render(scene, o);
        ms.push_back(r.frameMilliseconds);
        passes.push_back(r.timings);
        progress.advance();
      }
      FullFrameTiming t;
      t.method = method == SkyMethod::SkyViewLut ? "lut" : "per-pixel";
      t.width = big.width;
      t.height = big.height;
      t.frameMs = median(ms);
      t.passes = passes[medianIndex(ms)];
      result.fullFrame.push_back(std::move(t));
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace firmament
