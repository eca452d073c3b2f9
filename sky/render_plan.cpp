#include "sky/render_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clouds/cloud_settings.h"
#include "sky/scene_cloud_medium.h"
#include "sky/scene_view.h"
#include "sky/terrain_plan.h"

namespace firmament {

double twilightTablesWeight(double sunAltitudeDeg) {
  const double t = std::clamp(
      (kTwilightTablesAboveDeg - sunAltitudeDeg) / (kTwilightTablesAboveDeg - kTwilightTablesBelowDeg), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

double sceneTablesWeight(const Scene& scene, const PlanOptions& options, std::string* reason) {
  auto say = [&](const std::string& text) {
    if (reason) *reason = text;
  };
  if (options.multipleScattering == MultipleScattering::BrunetonTables) {
    say("--multiple-scattering tables");
    return 1.0;
  }
  if (options.multipleScattering == MultipleScattering::HillaireFms) {
    say("--multiple-scattering fms");
    return 0.0;
  }
  if (sceneHasCloudLayers(scene) || scene.hasSection("terrain")) {
    say("clouds and terrain read the f_ms path: the 4D tables are not used");
    return 0.0;
  }
  const double altitude =
      std::asin(std::clamp(makeSceneView(scene).sunDirection.z, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
  const double w = twilightTablesWeight(altitude);
  char text[200];
  if (w <= 0.0)
    std::snprintf(text, sizeof(text), "the sun is %.1f deg high: f_ms alone from %+.0f deg up (the 4D tables below it)",
                  altitude, kTwilightTablesAboveDeg);
  else if (w >= 1.0)
    std::snprintf(text, sizeof(text), "the sun is at %.1f deg: the 4D tables alone from %+.0f deg down", altitude,
                  kTwilightTablesBelowDeg);
  else
    std::snprintf(text, sizeof(text),
                  "the sun is at %.1f deg, in the hand-over from %+.0f to %+.0f deg: tables weight %.3f", altitude,
                  kTwilightTablesAboveDeg, kTwilightTablesBelowDeg, w);
  say(text);
  return w;
}

bool RenderPlan::has(const std::string& name) const {
  for (const auto& p : passes)
    if (p.name == name) return true;
  return false;
}

RenderPlan planRender(const Scene& scene, const PlanOptions& options) {
  RenderPlan plan;
  // The atmosphere is always present; its tables depend on its parameters only.
  plan.passes.push_back(
      {"atmosphere/transmittance_lut", "transmittance table T(r, mu)", "every sky needs sunlight attenuation", false});
  std::string tablesReason;
  const double weight = sceneTablesWeight(scene, options, &tablesReason);
  const bool fms = options.multipleScattering != MultipleScattering::BrunetonTables;
  const int batches = std::max(options.spectralSamples / 3, 1);
  const std::string each =
      batches > 1 ? " (once per batch of 3 of the " + std::to_string(options.spectralSamples) + " wavelengths)" : "";
  if (weight > 0.0) {
    const int orders = options.scatteringOrders;
    const std::string higher = orders >= 2 ? "orders 2.." + std::to_string(orders) : "";
    const std::string& tableEach = each;
    plan.passes.push_back({"atmosphere/direct_irradiance", "sunlight on the ground (lights order 2)",
                           "Bruneton 2017 tables" + tableEach, false});
    plan.passes.push_back({"atmosphere/single_scattering", "4D single Rayleigh and Mie scattering tables",
                           "Bruneton 2017 tables, order 1" + tableEach, false});
    if (orders >= 2) {
      plan.passes.push_back({"atmosphere/scattering_density", "4D scattering density J_n",
                             "Bruneton 2017 tables, " + higher + " (one dispatch each)" + tableEach, false});
      plan.passes.push_back({"atmosphere/indirect_irradiance", "ground sky irradiance table E(r, mu_s)",
                             "skylight on the ground, orders 1.." + std::to_string(orders - 1) + tableEach, false});
      plan.passes.push_back({"atmosphere/multiple_scattering", "4D scattering table, orders summed",
                             "Bruneton 2017 tables, " + higher + " (one dispatch each)" + tableEach, false});
    }
  } else if (options.multipleScattering == MultipleScattering::Auto) {
    plan.omitted.push_back(
        {"atmosphere/direct_irradiance .. atmosphere/multiple_scattering (the 4D tables)", tablesReason});
  }
  if (!fms) {
    plan.passes.push_back(
        {"sky/render_sky_tables", "HDR image (cd/m^2)", "the view from table lookups: sky, ground and sun disc", true});
    plan.omitted.push_back({"atmosphere/multiple_scattering_lut",
                            "multiple scattering comes from the 4D tables (--multiple-scattering tables)"});
  } else {
    const std::string why =
        weight >= 1.0 ? " (" + tablesReason + ": for the night's moonlit sky and ground light)" : "";
    plan.passes.push_back({"atmosphere/multiple_scattering_lut", "multiple-scattering table Psi_ms(r, mu_s)",
                           "light scattered more than once (Hillaire 2020): the first order" + each + why, false});
    if (options.multipleScatteringOrders > 1)
      plan.passes.push_back(
          {"atmosphere/multiple_scattering_order",
           "Psi_ms orders 2.." + std::to_string(options.multipleScatteringOrders),
           "each order marches through the previous one's table; a geometric tail after the last" + each, false});
    else
      plan.omitted.push_back({"atmosphere/multiple_scattering_order", "one order: Hillaire's f_ms series"});
    plan.passes.push_back({"atmosphere/fms_sky_irradiance", "ground sky irradiance table E(r, mu_s)",
                           "skylight on the ground, from the same single + Psi_ms sky" + each, false});
    // The sky-view table holds the sky seen from inside the atmosphere; from above it every pixel marches.
    const double cameraAltitude = scene.number("/location/height_m") + scene.number("/camera/height_above_ground_m");
    const bool inside = cameraAltitude <= scene.number("/atmosphere/thickness_m");
    if (weight >= 1.0) {
      plan.omitted.push_back({"sky/sky_view_lut, sky/render_sky", tablesReason});
    } else if (options.skyViewLut && inside) {
      plan.passes.push_back({"sky/sky_view_lut", "sky-view table (azimuth from the sun, zenith angle), Rec.709",
                             "the sky from the camera's altitude, marched once per texel" + each, true});
      plan.passes.push_back(
          {"sky/render_sky", "HDR image (cd/m^2)", "the view: one sky-view lookup per pixel, plus the sun disc", true});
    } else {
      plan.passes.push_back({"sky/render_sky_march", "HDR image (cd/m^2)",
                             std::string("the view: a march per pixel") +
                                 (inside ? "" : " (camera above the atmosphere)") + each + ", plus the sun disc",
                             true});
    }
    if (weight > 0.0)
      plan.passes.push_back({"sky/render_sky_tables", "HDR image (cd/m^2)",
                             weight >= 1.0 ? "the view from the 4D tables' lookups" + each + ": " + tablesReason
                                           : "the view from the 4D tables' lookups" + each +
                                                 ", blended over the f_ms sky: " + tablesReason,
                             true});
  }

  if (scene.hasSection("clouds")) {
    // docs/clouds/README.md: noise baked once per seed, then one march per frame (per spectral batch).
    if (options.multipleScattering == MultipleScattering::BrunetonTables) {
      plan.unavailable.push_back({"clouds", "clouds need the f_ms path (--multiple-scattering fms) in this version"});
    } else if (scene.at("/clouds/layers").empty()) {
      plan.omitted.push_back({"clouds", "the clouds section has no layers"});
      plan.omitted.push_back(
          {"sky/aerial_perspective_volume", "nothing at a finite distance reads it (no cloud layers, no terrain)"});
    } else {
      plan.passes.push_back(
          {"clouds/bake_noise_3d",
           "shape 128^3 and detail 32^3 RGBA noise (+ CPU blue noise); once per seed, or read from the disk cache",
           "cloud density, tileable, from the clouds seed", false});
      plan.passes.push_back({"clouds/bake_curl", "curl noise 128^2; once per seed, or read from the disk cache",
                             "distorts the detail noise", false});
      plan.passes.push_back({"clouds/downsample_noise_3d", "mip chains of the shape and detail noise, down to 4^3",
                             "the noise LOD by distance (lookups at the view step's footprint)", false});
      const AerialPerspective aerial = options.aerialPerspective
                                           ? *options.aerialPerspective
                                           : aerialPerspectiveFromName(scene.string("/clouds/aerial_perspective"));
      const std::string each = options.spectralSamples > 3 ? " (once per batch of 3 wavelengths)" : "";
      if (aerial == AerialPerspective::Volume)
        plan.passes.push_back({"sky/aerial_perspective_volume",
                               "aerial-perspective volume (32x32 froxel columns x 32 depth slices by default): air "
                               "light, Rec.709, and transmittance",
                               "the air in front of the clouds, marched once per froxel column" + each, true});
      else
        plan.omitted.push_back({"sky/aerial_perspective_volume",
                                aerial == AerialPerspective::March
                                    ? "aerial perspective 'march': the cloud march marches the air per pixel"
                                    : "aerial perspective 'off'"});
      // With terrain the map is baked always: the ground's cloud shadows read it (sky/terrain_pass.h).
      const bool shadowMap = scene.hasSection("terrain") ||
                             (options.cloudShadowMap ? *options.cloudShadowMap : scene.boolean("/clouds/shadow_map"));
      if (shadowMap)
        plan.passes.push_back({"clouds/bake_shadow_map",
                               "Beer shadow map: front depth, mean extinction, optical depth to the sun",
                               "the light march reads the sun's optical depth through all layers from it", true});
      else
        plan.omitted.push_back({"clouds/bake_shadow_map", "/clouds/shadow_map off: the light march alone"});
      const size_t layerCount = scene.at("/clouds/layers").size();
      const CloudMarchSettings defaults;
      const bool throughOthers = options.cloudLightThroughOtherLayers.value_or(defaults.lightThroughOtherLayers);
      if (layerCount > 1 && throughOthers && options.cloudOtherLayerMap.value_or(defaults.otherLayerMap))
        plan.passes.push_back({"clouds/bake_other_layers",
                               "the other layers' optical depth to the sun along each sun line (1 in 4 to 16 of its "
                               "rows per frame in a sequence)",
                               "a layer above shadows the one below: the light march reads the crossings from it",
                               true});
      else
        plan.omitted.push_back(
            {"clouds/bake_other_layers", layerCount < 2   ? "one layer: no other layer shadows it"
                                         : !throughOthers ? "light through the other layers off"
                                                          : "the other layers' map off: the light march crosses them"});
      const bool columnMap = options.cloudColumnMap.value_or(defaults.columnMap);
      const bool octaves = scene.integer("/clouds/lighting/ms_octaves") > 1;
      if (columnMap && octaves)
        plan.passes.push_back(
            {"clouds/bake_columns",
             "each layer's optical depth from K levels up to its top, per column (1 in 4 to 16 of its rows per frame "
             "in a sequence)",
             "the octaves' way from the layer top and the diffusion floor read the vertical optical depths from it",
             true});
      else
        plan.omitted.push_back({"clouds/bake_columns", !octaves
                                                           ? "one octave: no way from the top, no diffusion floor"
                                                           : "the column map off: the light march goes up and down"});
      if (columnMap && octaves && layerCount > 1)
        plan.passes.push_back({"clouds/bake_column_ambient",
                               "per column and layer, the other layers' depths above and below as the ambient's slab "
                               "sees them (9 columns each)",
                               "the ambient: a deck above dims the sky a layer below sees", true});
      else
        plan.omitted.push_back(
            {"clouds/bake_column_ambient", layerCount < 2 ? "one layer: no other layer dims its ambient"
                                                          : "no column map: each layer's ambient is its own slab"});
      if (options.cloudDeepShadowMap.value_or(defaults.deepShadowMap))
        plan.passes.push_back({"clouds/bake_deep_shadow",
                               "each layer's optical depth from K levels up to its top along each sun line (1 in 4 to "
                               "16 of its rows per frame in a sequence)",
                               "the light march takes its first steps and reads the rest of the way to the sun from it",
                               true});
      else
        plan.omitted.push_back(
            {"clouds/bake_deep_shadow", "the deep shadow map off: the light march takes every step"});
      const bool shafts = options.cloudLightShafts ? *options.cloudLightShafts : scene.boolean("/clouds/light_shafts");
      if (shadowMap && shafts && aerial == AerialPerspective::Volume)
        plan.passes.push_back(
            {"sky/cloud_light_shafts", "the sky image with the clouds' shadows in the air (light shafts)",
             "the aerial-perspective volume shadowed through the Beer shadow map; the sky scaled by what that removed",
             true});
      else
        plan.omitted.push_back({"sky/cloud_light_shafts", !shadowMap ? "light shafts need /clouds/shadow_map"
                                                          : !shafts
                                                              ? "/clouds/light_shafts off"
                                                              : "light shafts need /clouds/aerial_perspective volume"});
      plan.passes.push_back(
          {"clouds/render_clouds", "clouds composited over the sky image (cd/m^2)",
           std::to_string(scene.at("/clouds/layers").size()) +
               " layer(s): view march, light march, octave multiple scattering, aerial perspective (" +
               aerialPerspectiveName(aerial) + ")" + each,
           true});
      const int divisor = options.cloudResolutionDivisor ? *options.cloudResolutionDivisor
                                                         : int(scene.integer("/clouds/resolution_divisor"));
      if (divisor > 1)
        plan.passes.push_back({"clouds/upsample_clouds", "the clouds at full size, composited over the sky image",
                               "the march ran at 1/" + std::to_string(divisor) + " of the width and height", true});
      const int update =
          options.cloudTemporalUpdate ? *options.cloudTemporalUpdate : int(scene.integer("/clouds/temporal_update"));
      if (update > 1 && divisor == 1)
        plan.passes.push_back(
            {"clouds/temporal_resolve",
             "the clouds at full size from this frame's samples and the last frame's, composited",
             "frames that continue a sequence march 1 in " + std::to_string(update) +
                 " pixels and reproject the rest (a still, the first frame and a camera inside a layer march all)",
             true});
      else
        plan.omitted.push_back({"clouds/temporal_resolve",
                                update == 1
                                    ? "/clouds/temporal_update 1: every pixel marched every frame"
                                    : "/clouds/resolution_divisor above 1: the reduced grid marched every frame"});
    }
  } else {
    plan.omitted.push_back({"clouds", "no clouds section: no noise textures, cloud march or shadow map"});
    plan.omitted.push_back(
        {"sky/aerial_perspective_volume", "nothing at a finite distance reads it (no clouds, no terrain)"});
  }
  const bool cloudLayers =
      sceneHasCloudLayers(scene) && options.multipleScattering != MultipleScattering::BrunetonTables;
  if (scene.hasSection("weather") && cloudLayers) {
    plan.passes.push_back({"weather/simulate (CPU)", "the weather map the clouds read (coverage, type, top)",
                           "simulated from the local solar midnight to the scene's time", false});
  } else if (scene.hasSection("weather")) {
    plan.unavailable.push_back(
        {"weather", "the weather map only feeds clouds; run `firmament weather` to simulate it"});
  } else {
    plan.omitted.push_back({"weather", "no weather section: no simulation"});
  }
  {
    // The night (sky/night_plan.h): the moonlit sky is a second sky-view table.
    const double altitude = scene.number("/location/height_m") + scene.number("/camera/height_above_ground_m");
    const bool skyView = options.multipleScattering != MultipleScattering::BrunetonTables && options.skyViewLut &&
                         altitude <= scene.number("/atmosphere/thickness_m");
    planNight(decideNight(scene, options.night, skyView), plan);
  }
  if (scene.hasSection("terrain") && options.multipleScattering == MultipleScattering::BrunetonTables) {
    plan.unavailable.push_back({"terrain", "terrain needs the f_ms path (--multiple-scattering fms) in this version"});
  } else if (scene.hasSection("terrain")) {
    addTerrainPasses(scene, plan);
  } else {
    plan.omitted.push_back({"terrain", "no terrain section: the ground is the atmosphere's smooth sphere"});
  }
  return plan;
}

std::string describePlan(const RenderPlan& plan) {
  std::string out = "passes:\n";
  int index = 1;
  for (const auto& p : plan.passes)
    out += "  " + std::to_string(index++) + ". " + p.name + (p.perFrame ? "" : " [cached by parameter hash]") +
           "\n       -> " + p.output + "; " + p.reason + "\n";
  if (!plan.omitted.empty()) {
    out += "left out:\n";
    for (const auto& o : plan.omitted) out += "  - " + o.name + ": " + o.reason + "\n";
  }
  if (!plan.unavailable.empty()) {
    out += "not available yet:\n";
    for (const auto& o : plan.unavailable) out += "  - " + o.name + ": " + o.reason + "\n";
  }
  return out;
}

}  // namespace firmament
