#pragma once
// Cloud layers and the cloud render knobs, from a scene's "clouds" section (core/scene_schema.json;
// docs/clouds.md explains each), and their conversion to the shared CloudLayer structs
// (common/cloud_density.glsl) that the GPU march and the CPU path tracer both read.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/cloud_density.glsl"
#include "core/scene.h"

namespace firmament {

struct CloudLayerSettings {
  int kind = shared::kCloudCumulus;
  double bottom_m = 1500.0;  // above the ground sphere
  double top_m = 4000.0;
  double coverage = 0.5;
  double extinctionScale = 1.0;
  double density = 1.0;
  double anvil = 1.0;
  // Octave multiple-scattering parameters a <= b, c (common/cloud_lighting.glsl): the scene's
  // /clouds/lighting/ms_a|b|c where given, else the type's calibrated values (cloudTypeMultipleScattering).
  // msD: the weight of the Eddington diffusion floor under the octaves i >= 1 (cloudEddingtonSlabSource;
  // 0: off, 1: the slab's own value), /clouds/lighting/ms_d or the type's.
  // msR, msRA: the weight r and depth scale a_r of the light the cloud behind a sample (along the sun)
  // turns back towards the sun (cloudReflectedSource; 0: off), /clouds/lighting/ms_r|ms_ra or the type's.
  // msLowSunMu: the octaves' low-sun scale's mu_0 (cloudOctaveLowSunScale; 0: off),
  // /clouds/lighting/ms_low_sun_mu or the type's.
  double msA = 0.5, msB = 0.5, msC = 0.5, msD = 0.0, msR = 0.0, msRA = 0.0, msLowSunMu = 0.0;
};

// How the air between the camera and the clouds is applied (docs/clouds.md "Aerial perspective"):
// Volume reads the per-frame aerial-perspective volume (sky/aerial_perspective_volume.h, default),
// March marches the air per pixel (CloudMarchSettings::aerialPerspectiveSteps), Off leaves it out.
// Each is its own compiled variant of the march (a uniform branch costs both sides on lavapipe).
enum class AerialPerspective { Off, March, Volume };
AerialPerspective aerialPerspectiveFromName(const std::string& name);  // "volume", "march", "off"; InputError otherwise
const char* aerialPerspectiveName(AerialPerspective mode);

// Light and march knobs of the fast path (the quality preset fills the step counts).
struct CloudMarchSettings {
  int viewSteps = 64;    // N: a vertical crossing of the thickest layer takes about N fine steps
  int lightSteps = 6;    // light-march samples towards the sun
  int coarseFactor = 4;  // a coarse (empty-space) step is this many fine steps; 1 = no skipping
  // A coarse step skips its span only where its shape-only sample lies below the shape's edge by more
  // than emptySpaceMargin x span / (thickest layer's thickness), in units of the unclamped shape density
  // (cloudShapeSignedDensity). 0: skip wherever the sample is outside (at a sunset it lost
  // thin fringes, single scattering -16 %). 0.4: the margin is 0.025 at the nearest spans, 0.2 at the
  // farthest; bench clouds measured the same images for 0.05 fixed, 0.4, 0.8 and 1.6, and as with no
  // skipping at all, for +0.4 to +1 % samples (docs/clouds.md, "Empty-space skipping").
  double emptySpaceMargin = 0.4;
  // δ-scaled transport for a phase with a narrow forward peak (cloudPhaseDeltaFraction > 0: the
  // approximate Mie phase): the peak's share f of scattering goes straight on, so the sun's light march
  // and the view ray's in-scattered light see sigma_t (1 - f omega), while the single scattering keeps
  // the scene's phase (TMS, as the path tracer) and the alpha the true transmittance. Off: every path
  // attenuated by the full sigma_t, which darkened the approximate Mie clouds (docs/clouds.md "Phase").
  bool deltaScaling = true;
  double earlyExitTransmittance = 0.01;
  // At the early exit, the light still to come estimated as a continuation of the last sample's cloud
  // (T times its source over its extinction, the step integral's limit) and the alpha set to 0;
  // off: dropped, the alpha left at T (docs/clouds.md "Early exit").
  bool earlyExitRemainder = true;
  double maxDistance_m = 80000.0;  // clouds farther along the view ray are not drawn
  // tan of the light cone's half-angle (Schneider 2015's cone sampling). 0 by default: the cone's
  // sideways offsets grow with the distance along the sun ray and biased single scattering against the
  // path tracer (+6 % at noon; at a grazing sun the far samples land kilometres off the ray).
  double lightCone = 0.0;
  // The light march runs from the sample to where the sun ray leaves the sample's layer, at most
  // lightMaxLength_m (common/cloud_lighting.glsl cloudSunExitDistance). Off: the first milestone's
  // fixed length (the thickest layer's thickness, at most 4 km), too short for a low sun; kept for
  // comparisons (bench clouds).
  bool lightMarchToExit = true;
  // With lightMarchToExit: lightSteps per layer thickness of the way to the exit, from lightSteps up to
  // 4 lightSteps (a low sun's long ways get more samples; docs/clouds.md "Lighting"). Off: lightSteps
  // whatever the length (the fixed-step baseline's light march).
  bool lightStepsPerThickness = true;
  // The light march also crosses the other layers on the sun ray (lightSteps equal steps per layer
  // thickness of each crossing, 2 to 4 lightSteps): a deck above shadows the one below, as in the path
  // tracer. Off: each sample sees only its own layer. Not used where the Beer shadow map
  // covers the sample (the map has every layer). docs/clouds.md "Light through other layers".
  bool lightThroughOtherLayers = true;
  // The other layers' crossings take lightSteps x this scale per layer thickness of each (2 to 4 times
  // that). 2, since the crossings come from a map baked once per frame
  // (otherLayerMap): it halves their Jensen bias (two_layers' single scattering +15 % -> +7 %) for one
  // more bake's samples, not more per lit sample (docs/clouds.md "Light through other layers").
  double otherLayerLightStepsScale = 2.0;
  // The other layers' crossings from a map baked once per frame (clouds/other_layer_map.glsl): every
  // point on one line along the sun shares its crossing of a layer above, so a 2D map of the lines
  // (a plane through the camera, perpendicular to the sun, log-warped out to maxDistance_m) holds them
  // all, marched with the same steps. Off: each lit sample marches the crossings itself. docs/clouds.md "The other
  // layers' map".
  bool otherLayerMap = true;
  int otherLayerMapSize = 256;  // texels per side
  // The vertical optical depths (the octaves' way down from the layer top, the diffusion floor) from a
  // map baked once per frame (clouds/column_map.glsl): per column (a direction from the planet centre,
  // log-warped around the camera as the other layers' map) and layer, the optical depth from K + 1
  // levels up to the top. Off: each lit sample marches up (lightSteps / 2 samples) and down (2).
  // docs/clouds.md "The column map".
  bool columnMap = true;
  int columnMapSize = 256;  // texels per side
  int columnMapLevels = 8;  // K: levels per layer (K samples per column)
  // The far part of each lit sample's light march through its own layer from a map baked once per frame
  // (clouds/deep_shadow_map.glsl, a deep shadow map of optical depth): per sun line (the other layers'
  // map's plane) and layer, the optical depth from K + 1 levels up to the top. The march takes the first
  // deepShadowNearSteps of its n steps (the shadow's detail next to the sample, up to L (near / n)^2)
  // and the rest of the way from the map in one lookup. Off: every step marched.
  // docs/clouds.md "The deep shadow map".
  bool deepShadowMap = true;
  int deepShadowMapSize = 256;   // texels per side
  int deepShadowMapLevels = 16;  // K: levels per layer (K samples per line)
  int deepShadowNearSteps = 3;   // light-march steps marched before the map takes over
  double lightMaxLength_m = 40000.0;
  // Longer view steps behind dense cloud: once the view ray's δ-scaled transmittance T falls below
  // T1 = lowTransmittanceStepStart, the fine step is multiplied by min(T1 / T, K), K =
  // lowTransmittanceStepMax (common/cloud_march.glsl cloudLowTransmittanceStepFactor; docs/clouds.md
  // "Longer steps behind dense cloud"). 0: off. The default T1 0.1, K 4: the bench's errors
  // against the path tracer move by at most 0.005, the stills are 5-19 % faster; larger T1 and K save
  // more but a long step through patchy cloud is biased bright (Jensen's inequality).
  double lowTransmittanceStepStart = 0.1;
  double lowTransmittanceStepMax = 4.0;
  // Octaves i >= 1 of the multiple-scattering approximation (docs/clouds.md "Multiple scattering"):
  // msZenithDepth: the better of the sun ray (E, tau_sun) and the way down from the layer top (E mu_s,
  // tau_up by a second march of lightSteps / 2 samples, at least 2, straight up); msScatteredOnly: the
  // octave's attenuation without its unscattered part, e^(-a^i tau) - e^(-tau).
  bool msZenithDepth = true;
  bool msScatteredOnly = true;
  // The higher orders' build-up along the view ray (common/cloud_lighting.glsl cloudBuildUpDecay;
  // docs/clouds.md "Build-up along the view"): the octaves' and the floor's source at a sample times
  // 1 - e^(-k tau_behind), tau_behind the view ray's optical depth behind the sample. k = 4
  // has the least summed squared error of 1, 2, 3, 4, 6 and 10 over the seven cumulus and six
  // stratocumulus calibration scenes with the shipped constants (rms rel RMSE cumulus 0.1420 -> 0.1338,
  // stratocumulus 0.1818 -> 0.1791; on the eleven cumulus scenes since, 0.1467 -> 0.1410). 0: off.
  double msBuildUpScale = 4.0;
  // The ambient's sky and ground weights from the layer as a conservative slab under diffuse light
  // (common/cloud_lighting.glsl cloudAmbientGroundWeight, from the column's optical depths up and down)
  // instead of visibilities linear in the height (CloudLightingSettings::ambientBottomVisibility).
  // Against the path tracer with the sky and ground (bench rows `ambient`):
  // the light the ambient adds 0.84 -> 1.11 of the path tracer's at noon, 1.09 -> 0.99 at the sunset,
  // 0.75 -> 1.02 under the overcast; docs/clouds.md "Lighting".
  bool ambientSlab = true;
  // The slab's depths up and down include the other layers' whole columns above and below (the column
  // map's, column_map.glsl columnMapOtherLayersOpticalDepths): a deck above dims the sky a layer below
  // sees. Only with the column map (octaves > 1); without it each layer is its own slab.
  bool ambientThroughOtherLayers = true;
  // The slab's net flux turned towards the camera by the phase's forward lobe (common/cloud_lighting.glsl
  // cloudAmbientViewGroundWeight), times this; 0: the slab's mean radiance J alone.
  double ambientFlow = 1.0;
  // The octaves' (i >= 1) and the reflected light's sunlight scaled by min(1, mu_s / mu_0)
  // (cloudOctaveLowSunScale). Under a low sun the octaves gave up to three times the path tracer's
  // higher orders in cumulus fields (bench scenario cumulus_low_sun, the calibration's low-sun scenes).
  // mu_0 is per layer (CloudLayerSettings::msLowSunMu: the type's fit, cumulus 0.358,
  // or the scene's ms_low_sun_mu). This, where >= 0, overrides it for every layer (0: off everywhere; the
  // option); negative: each layer's own.
  double octaveLowSunMu = -1.0;
  // Under that low-sun scale s < 1 the reflected light's depth scale a_r becomes a_r / s too
  // (cloudReflectedLowSunDepthScale): the sun line then crosses kilometres of broken field, and the light
  // reflected back from deep along it was what stayed too bright (the view away from a sun 82 deg
  // from the zenith +26 %, its far cloud bases 2.1x). Off: a_r whatever the sun.
  bool reflectedLowSunDepth = true;
  // Step schedule (common/cloud_march.glsl): the fine step is H / N up to one thickness H from the
  // camera, then grows in proportion to the distance up to maxStepFactor H / N. uniformSteps: the first
  // milestone's schedule instead, N equal steps over the ray's total length inside the shells.
  double maxStepFactor = 8.0;
  bool uniformSteps = false;
  // Beer shadow map (common/cloud_shadow.glsl): when on, the light march reads the sun's optical depth
  // through all layers from the map (baked per frame) wherever the sample lies on it.
  bool beerShadowMap = false;
  // With the Beer shadow map and the aerial-perspective volume: the clouds' shadows in the air (light
  // shafts; sky/cloud_light_shafts.comp). The scene's /clouds/light_shafts.
  bool lightShafts = true;
  int shadowMapSize = 256;             // texels per side
  int shadowMapSteps = 128;            // march steps per texel
  double shadowMapExtent_m = 40000.0;  // side of the square (m), centred above the camera
  // Compile out of the march the options this frame does not use (clouds/cloud_pass.cpp
  // cloudMarchFeatures; a specialization constant of render_clouds.glsl): lavapipe runs every branch
  // under a mask, so unused options cost time. Off: one general pipeline, the same image bit for bit
  // (test CloudRender.SpecializedMarchMatchesTheGeneralOne).
  bool specializeMarch = true;
  bool jitter = true;  // blue-noise jitter of the sample positions
  // Noise LOD by distance (the "LOD mips"): a view sample and its light marches read the shape
  // and detail textures' mip level log2(s h / texel) (the nearest level, at least 0), h the view step
  // there (it grows with the distance, common/cloud_march.glsl) and s this scale. 0: level 0 everywhere
  // (the path tracer's field). 1: the same errors against the path tracer,
  // 0.07-0.22 % from level 0 at 640x360, 4-7 % faster on lavapipe where clouds are far, noon within the
  // timing noise (docs/clouds.md "Noise LOD").
  double noiseLodScale = 1.0;
  // The march runs on a grid this many times coarser in x and y (1, 2 or 4), each of its pixels at the
  // centre of the image pixels it stands for, then is interpolated bilinearly to the image
  // (clouds/upsample_clouds). The scene's /clouds/resolution_divisor.
  int resolutionDivisor = 1;
  // Temporal reprojection (docs/clouds.md "Temporal reprojection"; the scene's /clouds/temporal_update):
  // a frame that continues a sequence (SkyRenderOptions::continueSequence) marches 1 in N of the pixels
  // (N = 1, 4 or 16: one pixel of every 1x1, 2x2 or 4x4 block, cycling) and takes the rest from the
  // previous frame, reprojected with the camera's and the wind's motion and clamped to the fresh
  // samples around. 1: every pixel, every frame. With resolutionDivisor > 1 the reduced grid is marched
  // every frame instead.
  int temporalUpdate = 1;
  bool temporalClamp = true;  // clamp the reprojected history to the fresh samples around (off: comparisons)
  AerialPerspective aerialPerspective = AerialPerspective::Volume;  // the scene's /clouds/aerial_perspective
  int aerialPerspectiveSteps = 8;  // March: equal steps from the camera to the cloud's mean depth
  bool ambient = true;
};

// The droplets' phase function (common/cloud_lighting.glsl cloudPhase; the scene's
// /clouds/lighting/phase): two Henyey-Greenstein lobes (default), or Jendersie and d'Eon 2023's
// approximate Mie phase for a droplet diameter (/clouds/lighting/droplet_diameter_um).
enum class CloudPhaseModel { DualHenyeyGreenstein, ApproximateMie };
// "dual_henyey_greenstein" or "approximate_mie"; otherwise InputError("<what>: '<name>'; allowed: ...").
CloudPhaseModel cloudPhaseModelFromName(const std::string& name, const std::string& what);

struct CloudLightingSettings {
  CloudPhaseModel phase = CloudPhaseModel::DualHenyeyGreenstein;
  double dropletDiameter_um = 20.0;  // ApproximateMie: fills the lobes below when the scene is read
  // The phase's lobes, p = (1 - backWeight) p_HG(gForward) + backWeight p_Draine(gBack, alpha):
  // the dual-HG model's forward and back lobes (alpha = 0), or the approximate Mie's HG and Draine lobes.
  double gForward = 0.8;
  double gBack = -0.3;
  double backWeight = 0.3;
  double alpha = 0.0;
  double albedo = 1.0;
  int octaves = 3;  // a, b, c are per layer (CloudLayerSettings::msA, msB, msC)
  double ambientBottomVisibility = 0.5;
};

// The share f = (1 - backWeight) g^2 of all scattering that δ-HG scaling (Joseph, Wiscombe and Weinman
// 1976) sends straight on when the first lobe is at least minG forward; 0 otherwise. The path tracer
// (CloudReferenceSettings::deltaLobeMinG) and the march (CloudMarchSettings::deltaScaling) share it.
double cloudPhaseDeltaFraction(const CloudLightingSettings& lighting, double minG = 0.95);

struct CloudSettings {
  std::vector<CloudLayerSettings> layers;
  uint32_t seed = 1;
  double shapeScale_m = 12000.0;
  double detailScale_m = 1500.0;
  double detailStrength = 0.35;
  double curlStrength_m = 150.0;
  double windSpeed_m_s = 0.0;
  double windFromDeg = 270.0;
  double time_s = 0.0;
  // The camera's horizontal offset over the clouds (m, east and north; /clouds/offset_east_m, _north_m):
  // added to the wind's offset, as if the camera stood this far from the location.
  double offsetEast_m = 0.0, offsetNorth_m = 0.0;
  double skew = 0.2;
  CloudLightingSettings lighting;
  CloudMarchSettings march;

  // From the scene's "clouds" section (which must be present). Throws InputError for layers with
  // top <= bottom, overlapping layers, or ms_a > ms_b.
  static CloudSettings fromScene(const Scene& scene);
};

// Overrides of the march from the command line or a benchmark (unset: the scene's preset).
struct CloudOverrides {
  std::optional<int> viewSteps;
  std::optional<int> lightSteps;
  std::optional<int> coarseFactor;
  std::optional<double> emptySpaceMargin;
  std::optional<bool> deltaScaling;
  std::optional<bool> jitter;
  std::optional<int> resolutionDivisor;
  std::optional<int> temporalUpdate;
  std::optional<bool> temporalClamp;
  std::optional<bool> uniformSteps;
  std::optional<double> maxStepFactor;
  std::optional<bool> beerShadowMap;
  std::optional<int> shadowMapSize;
  std::optional<double> shadowMapExtent;
  std::optional<bool> lightShafts;
  std::optional<AerialPerspective> aerialPerspective;
  std::optional<int> aerialPerspectiveSteps;
  std::optional<bool> ambient;
  std::optional<bool> lightMarchToExit;
  std::optional<bool> lightStepsPerThickness;
  std::optional<bool> lightThroughOtherLayers;
  std::optional<double> earlyExitTransmittance;
  std::optional<bool> earlyExitRemainder;
  std::optional<double> noiseLodScale;
  std::optional<double> lowTransmittanceStepStart;
  std::optional<double> lowTransmittanceStepMax;
  std::optional<double> otherLayerLightStepsScale;
  std::optional<bool> otherLayerMap;
  std::optional<int> otherLayerMapSize;
  std::optional<bool> columnMap;
  std::optional<int> columnMapSize;
  std::optional<int> columnMapLevels;
  std::optional<bool> deepShadowMap;
  std::optional<int> deepShadowMapSize;
  std::optional<int> deepShadowMapLevels;
  std::optional<int> deepShadowNearSteps;
  std::optional<double> lightCone;
  std::optional<bool> msZenithDepth;
  std::optional<bool> msScatteredOnly;
  std::optional<double> msBuildUpScale;
  std::optional<bool> ambientSlab;
  std::optional<bool> ambientThroughOtherLayers;
  std::optional<double> ambientFlow;
  std::optional<double> octaveLowSunMu;
  std::optional<bool> reflectedLowSunDepth;
  std::optional<bool> specializeMarch;
  void apply(CloudMarchSettings& march) const;
};

// Extinction at density 1 (m^-1, 550 nm; grey in the visible for droplets >> wavelength) per type.
// From liquid water content LWC and effective radius r_e, sigma = 3 LWC / (2 rho_w r_e) (Stephens 1978,
// extinction efficiency 2): cumulus LWC 0.5-1 g/m^3, r_e 10 um -> 0.075-0.15; stratus 0.3 g/m^3 -> 0.045.
double cloudTypeExtinction(int kind);
// The octave parameters a, b, c and the diffusion floor's weight d of a cloud type, fitted to the path
// tracer by `firmament bench clouds --calibrate` (eval/cloud_calibration.h; docs/clouds.md "Calibration"):
// cumulus, stratocumulus, stratus (since) and cirrus (since) on their own
// calibration scenes (the approximate Mie phase's stratus takes stratocumulus's, its cirrus the joint
// fit); cumulonimbus takes cumulus's. Per phase
// model: c scales the phase's lobes and the approximate Mie's transport is δ-scaled, so each phase has
// its own fit (`--phase`; the approximate Mie's d fitted in).
struct CloudMultipleScattering {
  double a, b, c, d;
  double r = 0.0, ra = 0.0;  // the reflected light's weight and depth scale (0: off)
  double lowSunMu = 0.0;     // the octaves' low-sun scale min(1, mu_s / mu_0): mu_0 (0: off)
};
// reflectedLight (/clouds/lighting/reflected_light, default true): the fit with the reflected light
// (cloudReflectedSource: cumulus, cumulonimbus, stratocumulus) where the type has one, else the octaves
// alone.
CloudMultipleScattering cloudTypeMultipleScattering(int kind,
                                                    CloudPhaseModel phase = CloudPhaseModel::DualHenyeyGreenstein,
                                                    bool reflectedLight = true);
// The joint fit over the cumulus and stratocumulus calibration scenes (the calibration's group "all").
CloudMultipleScattering cloudJointMultipleScattering(CloudPhaseModel phase = CloudPhaseModel::DualHenyeyGreenstein);
// The strength of the diffusion floor's limb darkening at a layer's base (cloudBaseLimbFactor; 1: as
// fitted to the Monte Carlo of a homogeneous slab): 1 for the layers that are slabs (stratus,
// stratocumulus), 0 for the others. Held out (1024-path references), the overcast went 0.053 -> 0.037
// with it; the cumulus noon 0.075 -> 0.085 and the cirrus 0.131 -> 0.137 when their types had it too
// (docs/clouds.md "Lighting", item 6).
double cloudTypeBaseLimbDarkening(int kind);
int cloudKindFromName(const std::string& name);  // "cumulus" -> kCloudCumulus; InputError if unknown
const char* cloudKindName(int kind);

// The shared layer structs for a ground sphere of radius groundRadius_m.
std::vector<shared::CloudLayer> sharedCloudLayers(const CloudSettings& settings, double groundRadius_m);

// The first milestone's light-march length (m): the thickest layer's thickness, at most 4 km
// (CloudMarchSettings::lightMarchToExit off).
double cloudLightMarchLength(const CloudSettings& settings);

// The thickest layer's thickness H (m, at least 1 m): the base view step is H / N.
double cloudThickestLayer(const CloudSettings& settings);

}  // namespace firmament
