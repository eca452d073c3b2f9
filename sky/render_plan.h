#pragma once
// A scene compiles to the list of passes it needs, and only those run: no clouds section, no noise
// textures, no cloud march, no shadow map. `firmament render --explain` prints the plan.
#include <string>
#include <vector>

#include <optional>

#include "clouds/cloud_settings.h"
#include "core/scene.h"
#include "sky/night_plan.h"

namespace firmament {

// How light scattered more than once is computed: Hillaire 2020's infinite-order isotropic f_ms table
// (Psi_ms) with a per-pixel march, or Bruneton 2017's N orders in 4D tables read without a march. Auto
// (the default): f_ms while the sun is up, the 4D tables when it is low or below the horizon, where f_ms
// spreads the multiply scattered light too evenly (decision 0158); clouds and terrain read f_ms always.
enum class MultipleScattering { HillaireFms, BrunetonTables, Auto };

// Auto: f_ms alone with the sun at or above kTwilightTablesAboveDeg, the 4D tables alone at or below
// kTwilightTablesBelowDeg, and between them the frame is (1 - w) f_ms + w tables, w a smoothstep in the
// sun's altitude (both computed, so there is no step through dusk).
inline constexpr double kTwilightTablesAboveDeg = -2.0;
inline constexpr double kTwilightTablesBelowDeg = -6.0;
double twilightTablesWeight(double sunAltitudeDeg);

// The render options that change which passes run.
struct PlanOptions {
  MultipleScattering multipleScattering = MultipleScattering::Auto;
  int scatteringOrders = 4;          // BrunetonTables and Auto's tables
  bool skyViewLut = true;            // HillaireFms: read a per-frame sky-view table (cameras inside the atmosphere)
  int spectralSamples = 3;           // HillaireFms: wavelengths, in batches of three
  int multipleScatteringOrders = 3;  // HillaireFms: Psi_ms orders iterated (1 = Hillaire's one pass)
  // Replaces the scene's /clouds/aerial_perspective (SkyRenderOptions::clouds.aerialPerspective).
  std::optional<AerialPerspective> aerialPerspective;
  // Replaces the scene's /clouds/resolution_divisor (SkyRenderOptions::clouds.resolutionDivisor).
  std::optional<int> cloudResolutionDivisor;
  // Replaces the scene's /clouds/shadow_map (SkyRenderOptions::clouds.beerShadowMap).
  std::optional<bool> cloudShadowMap;
  // Replaces the scene's /clouds/light_shafts (SkyRenderOptions::clouds.lightShafts).
  std::optional<bool> cloudLightShafts;
  // Replaces the scene's /clouds/temporal_update (SkyRenderOptions::clouds.temporalUpdate).
  std::optional<int> cloudTemporalUpdate;
  // The march's defaults unless set (SkyRenderOptions::clouds.lightThroughOtherLayers, .otherLayerMap).
  std::optional<bool> cloudLightThroughOtherLayers;
  std::optional<bool> cloudOtherLayerMap;
  std::optional<bool> cloudColumnMap;      // SkyRenderOptions::clouds.columnMap
  std::optional<bool> cloudDeepShadowMap;  // SkyRenderOptions::clouds.deepShadowMap
  NightOptions night;                      // SkyRenderOptions::night (sky/night_plan.h)
};

struct PlannedPass {
  std::string name;      // the pass and its shader, e.g. "atmosphere/transmittance_lut"
  std::string output;    // what it produces
  std::string reason;    // why this scene needs it
  bool perFrame = true;  // false: depends on parameters only, cached by their hash
};

struct OmittedPass {
  std::string name;
  std::string reason;
};

struct RenderPlan {
  std::vector<PlannedPass> passes;
  std::vector<OmittedPass> omitted;      // not needed by this scene
  std::vector<OmittedPass> unavailable;  // asked for by the scene, not implemented in this version
  bool has(const std::string& name) const;
};

RenderPlan planRender(const Scene& scene, const PlanOptions& options = {});

// The share of the 4D tables in the frame's clear sky: 1 for BrunetonTables, 0 for HillaireFms, and for
// Auto twilightTablesWeight at the scene's sun, 0 with cloud layers or terrain (they read f_ms). reason
// (optional) says why, for the plan.
double sceneTablesWeight(const Scene& scene, const PlanOptions& options, std::string* reason = nullptr);

// Human-readable listing (for --explain).
std::string describePlan(const RenderPlan& plan);

}  // namespace firmament
