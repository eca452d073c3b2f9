#include "eval/terrain_bench.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>

#include "atmosphere/atmosphere_spectra.h"
#include "clouds/cloud_settings.h"
#include "core/error.h"
#include "core/log.h"
#include "eval/scenarios.h"
#include "eval/terrain_reference.h"
#include "sky/scene_cloud_medium.h"
#include "sky/sky_renderer.h"

namespace firmament {
namespace {

struct Knob {
  std::string knob, value;
  std::function<void(SkyRenderOptions&)> apply;
};

std::vector<Knob> knobs(bool quick) {
  std::vector<Knob> k;
  k.push_back({"default", "shadow map 256 over 40 km, penumbra, hemisphere deck, self-shadow, horizon map 16, LOD 0.7",
               [](SkyRenderOptions&) {}});
  k.push_back(
      {"sky_occlusion", "none", [](SkyRenderOptions& o) { o.terrain.skyOcclusion = TerrainSkyOcclusion::None; }});
  k.push_back({"sky_occlusion", "horizon map 8", [](SkyRenderOptions& o) { o.terrain.horizonAzimuths = 8; }});
  for (int rays : quick ? std::vector<int>{8} : std::vector<int>{8, 32})
    k.push_back({"sky_occlusion", "rays " + std::to_string(rays), [rays](SkyRenderOptions& o) {
                   o.terrain.skyOcclusion = TerrainSkyOcclusion::Rays;
                   o.terrain.occlusionRays = rays;
                 }});
  k.push_back({"penumbra", "off", [](SkyRenderOptions& o) { o.terrain.penumbra = false; }});
  k.push_back({"self_shadow", "off", [](SkyRenderOptions& o) { o.terrain.selfShadow = false; }});
  k.push_back({"sky_light", "deck of the point's column",
               [](SkyRenderOptions& o) { o.terrain.skyLight = TerrainSkyLight::Deck; }});
  k.push_back(
      {"sky_light", "clear-sky table", [](SkyRenderOptions& o) { o.terrain.skyLight = TerrainSkyLight::Clear; }});
  for (int size : quick ? std::vector<int>{64, 1024} : std::vector<int>{64, 128, 512, 1024})
    k.push_back(
        {"shadow_map_size", std::to_string(size), [size](SkyRenderOptions& o) { o.clouds.shadowMapSize = size; }});
  k.push_back({"shadow_map_extent", "20 km", [](SkyRenderOptions& o) { o.clouds.shadowMapExtent = 20000.0; }});
  for (double footprint : quick ? std::vector<double>{0.0} : std::vector<double>{0.0, 1.0})
    k.push_back({"lod_footprint", footprint == 0.0 ? "0 (off)" : "1",
                 [footprint](SkyRenderOptions& o) { o.terrain.lodFootprint = footprint; }});
  return k;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::vector<std::string> scenarioNames(const TerrainBenchConfig& config) {
  std::vector<std::string> names;
  const nlohmann::json index = evalScenarioIndex("terrain");
  for (const auto& s : index.at("scenarios")) {
    const std::string name = s.at("name").get<std::string>();
    if (!config.scenario.empty() ? name == config.scenario : (!config.quick || s.at("quick").get<bool>()))
      names.push_back(name);
  }
  return names;
}

std::vector<std::string> overridesFor(const std::string& name, const TerrainBenchConfig& config) {
  std::vector<std::string> o;
  // Absolute: a relative path in a scene is taken from the scene file's folder.
  if (name.rfind("dem_", 0) == 0)
    o.push_back("/terrain/file=" + std::filesystem::absolute(config.demDir / "terra" / "elev.tif").string());
  if (config.quick) {
    const nlohmann::json index = evalScenarioIndex("terrain");
    const nlohmann::json& size = index.at("quick_size");
    o.push_back("/camera/width=" + std::to_string(size.at("width").get<int>()));
    o.push_back("/camera/height=" + std::to_string(size.at("height").get<int>()));
  }
  return o;
}

}  // namespace

void checkTerrainBenchConfig(const TerrainBenchConfig& config) {
  const std::vector<std::string> names = scenarioNames(config);
  if (names.empty()) {
    std::string all;
    const nlohmann::json index = evalScenarioIndex("terrain");
    for (const auto& s : index.at("scenarios")) {
      all += ' ';
      all += s.at("name").get<std::string>();
    }
    throw InputError("--scenario " + config.scenario + ": no such terrain scenario (" + all + " )");
  }
  for (const auto& n : names)
    if (n.rfind("dem_", 0) == 0 && !std::filesystem::exists(config.demDir / "terra" / "elev.tif"))
      throw InputError("bench terrain: scenario " + n + " needs " + (config.demDir / "terra" / "elev.tif").string() +
                       ": run scripts/fetch_test_dems.sh " + config.demDir.string() +
                       " (or give --dem-dir, or --scenario another one)");
}

std::vector<TerrainBenchRow> runTerrainBench(gpu::Context& context, const TerrainBenchConfig& config) {
  SkyRenderer renderer(context);
  std::vector<TerrainBenchRow> rows;
  const int directions = config.skyDirections > 0 ? config.skyDirections : (config.quick ? 16 : 64);
  for (const std::string& name : scenarioNames(config)) {
    const Scene scene = evalScenarioScene("terrain", name, overridesFor(name, config));
    // The reference of the scene's ground (knob-free: every knob changes only the fast path).
    SkyRenderOptions base;
    base.luts.spectralSamples = 3;  // the reference's three wavelengths
    base.terrain.groundOnly = true;
    const RenderResult first = renderer.render(scene, base);
    const SceneView& view = first.view;
    const terrain::ResolvedTerrain& resolved = renderer.terrainPass()->resolved();
    // The clouds over the atmosphere's ground (as the GPU's layers: sharedCloudLayers over its
    // bottom radius, the location's height), not over the field under the camera.
    SceneView cloudView = view;
    cloudView.cameraRadius = atmosphereParametersAt(view.atmosphere, kDefaultWavelengthsNm).bottom_radius +
                             scene.number("/camera/height_above_ground_m");
    const bool clouds = sceneHasCloudLayers(scene);
    const CloudMedium medium = clouds ? sceneCloudMedium(scene, cloudView, context, base.cloudNoise)
                                      : emptyCloudMedium(sceneGroundRadius(scene, cloudView));
    TerrainReferenceSettings rs;
    rs.skyDirections = directions;
    rs.pixelSide = config.referencePixelSide;
    rs.threads = config.threads;
    if (config.quick) rs.skyTableZenith = 8, rs.skyTableSamples = 4;
    const TerrainReferenceImage reference = renderTerrainReference(
        scene, view, resolved, medium, clouds ? CloudSettings::fromScene(scene).lighting : CloudLightingSettings{}, rs);
    logInfo("bench terrain: " + name + " reference (" + std::to_string(directions) + " sky directions/pixel) in " +
            std::to_string(reference.seconds) + " s");
    for (const Knob& k : knobs(config.quick)) {
      SkyRenderOptions o = base;
      k.apply(o);
      const RenderResult r = renderer.render(scene, o);
      const std::vector<float> depth = renderer.terrainPass()->depth().download<float>();
      const TerrainReferenceError e = compareWithTerrainReference(r.image, depth, reference);
      TerrainBenchRow row;
      row.scenario = name, row.knob = k.knob, row.value = k.value;
      row.pixels = e.pixels, row.shadowPixels = e.shadowPixels;
      row.relRmse = e.relRmse, row.noiseFloor = e.noiseFloor, row.noiseCorrected = e.noiseCorrected;
      row.meanBias = e.meanBias, row.shadowBias = e.shadowBias, row.litBias = e.litBias;
      row.meanReference = e.meanReference, row.meanTest = e.meanTest;
      row.referenceSeconds = reference.seconds;
      // Timing: the full frame (air included, the default spectral choice) at the timing size.
      SkyRenderOptions timed;
      k.apply(timed);
      timed.downloadImages = false;
      const std::vector<std::string> size = {"/camera/width=" + std::to_string(config.timingWidth),
                                             "/camera/height=" + std::to_string(config.timingHeight)};
      std::vector<std::string> overrides = overridesFor(name, config);
      overrides.insert(overrides.end(), size.begin(), size.end());
      const Scene timingScene = evalScenarioScene("terrain", name, overrides);
      std::vector<double> terrainMs, frameMs;
      for (int i = 0; i <= config.repeats; ++i) {
        const RenderResult t = renderer.render(timingScene, timed);
        if (i == 0) continue;  // warm-up: tables, noise, pipelines
        double ms = 0.0;
        for (const auto& p : t.timings)
          if (p.label.rfind("terrain/", 0) == 0) ms += p.milliseconds;
        terrainMs.push_back(ms);
        frameMs.push_back(t.frameMilliseconds);
      }
      row.terrainMs = median(terrainMs);
      row.frameMs = median(frameMs);
      char line[256];
      std::snprintf(line, sizeof(line),
                    "%-18s %-18s %-22s relRMSE %.3f (noise %.3f) bias %+.3f shadow %+.3f terrain %.1f ms", name.c_str(),
                    k.knob.c_str(), k.value.substr(0, 22).c_str(), row.noiseCorrected, row.noiseFloor, row.meanBias,
                    row.shadowBias, row.terrainMs);
      logInfo(line);
      rows.push_back(row);
    }
  }
  return rows;
}

void writeTerrainBenchOutputs(const TerrainBenchConfig& config, const std::vector<TerrainBenchRow>& rows,
                              const std::string& device) {
  std::ofstream csv(config.outDir / "terrain_results.csv");
  csv << "scenario,knob,value,pixels,shadow_pixels,rel_rmse,noise_floor,rel_rmse_noise_corrected,mean_bias,"
         "shadow_bias,lit_bias,mean_reference_cd_m2,mean_test_cd_m2,terrain_ms,frame_ms,reference_s\n";
  for (const auto& r : rows) {
    char line[512];
    std::snprintf(line, sizeof(line), "%s,%s,\"%s\",%d,%d,%.5g,%.5g,%.5g,%.5g,%.5g,%.5g,%.6g,%.6g,%.3f,%.3f,%.2f\n",
                  r.scenario.c_str(), r.knob.c_str(), r.value.c_str(), r.pixels, r.shadowPixels, r.relRmse,
                  r.noiseFloor, r.noiseCorrected, r.meanBias, r.shadowBias, r.litBias, r.meanReference, r.meanTest,
                  r.terrainMs, r.frameMs, r.referenceSeconds);
    csv << line;
  }
  std::ofstream md(config.outDir / "terrain_report.md");
  md << "# bench terrain\n\nDevice: " << device
     << ". Ground luminance at the surface (GPU `groundOnly`, 3 wavelengths) "
     << "against the CPU reference (eval/terrain_reference.h); rel RMSE with the reference's noise removed; "
     << "times: terrain passes and whole frame at " << config.timingWidth << "x" << config.timingHeight
     << ", median of " << config.repeats << ".\n";
  if (!config.environmentNote.empty()) md << "\n" << config.environmentNote << "\n";
  md << "\n| scenario | knob | value | pixels (shadowed) | rel RMSE | noise | mean bias | shadowed bias | lit bias | "
        "terrain ms | frame ms |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& r : rows) {
    char line[512];
    std::snprintf(line, sizeof(line),
                  "| %s | %s | %s | %d (%d) | %.3f | %.3f | %+.3f | %+.3f | %+.3f | %.1f | %.1f |\n",
                  r.scenario.c_str(), r.knob.c_str(), r.value.c_str(), r.pixels, r.shadowPixels, r.noiseCorrected,
                  r.noiseFloor, r.meanBias, r.shadowBias, r.litBias, r.terrainMs, r.frameMs);
    md << line;
  }
}

}  // namespace firmament
