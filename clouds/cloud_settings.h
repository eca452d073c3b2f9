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

// Light and march knobs of the fast path (the quality preset fills the step counts): one field per row
// of shaders/clouds/cloud_march_knobs.def, where each default's reasons are.
struct CloudMarchSettings {
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) type name = value;
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
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

// Overrides of the march from code: a benchmark, a test, a host (unset: the scene's or the preset's). One
// optional per row of shaders/clouds/cloud_march_knobs.def.
struct CloudOverrides {
#define FIRMAMENT_CLOUD_KNOB(type, name, value, lo, hi, scene, doc) std::optional<type> name;
#include "clouds/cloud_march_knobs.def"
#undef FIRMAMENT_CLOUD_KNOB
  // Sets march's fields from the optionals that are set. InputError (exit code 2) for a value out of its
  // knob's range: "cloud knob light_steps: 0 is out of range; allowed: integer in [1, 256]".
  void apply(CloudMarchSettings& march) const;
  // Sets the knob with this identifier (cloudMarchKnobs: "light_steps", "deep_shadow_map") from text
  // ("8", "0.5", "true", "volume"). InputError for an unknown identifier, a value that does not parse
  // or one out of range.
  void set(const std::string& id, const std::string& value);
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
