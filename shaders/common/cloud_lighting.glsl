// cloud_lighting.glsl: the pieces of cloud lighting shared by the GPU march, the CPU path tracer and
// the tests (compat.glsl rules). docs/clouds.md derives each formula.
#ifndef FIRMAMENT_CLOUD_LIGHTING_GLSL
#define FIRMAMENT_CLOUD_LIGHTING_GLSL

#include "common/atmosphere_medium.glsl"
#include "common/cloud_density.glsl"

SHARED_BEGIN

// Energy-conserving integration of one march step (Hillaire 2016, "Physically based sky, atmosphere
// and cloud rendering in Frostbite"). Over a step of length dt with constant
// extinction sigma_t and source S (radiance per metre of scattering), the light added at the step's
// start is
//     ∫_0^dt S e^(-sigma_t x) dx = S (1 - e^(-sigma_t dt)) / sigma_t = S * cloudStepIntegral(sigma_t, dt).
// Written as dt (1 - e^-k) / k with k = sigma_t dt, which is exact in both limits:
//   k -> 0:   dt (1 - k/2 + k^2/6 - k^3/24 + k^4/120 - ...) -> dt   (the thin medium: S dt);
//   k -> oo:  (1 - e^-k) / sigma_t -> 1 / sigma_t                    (the opaque step: S / sigma_t).
// Below k = 0.01 the Taylor series to k^4 is used: its truncation error k^5 / 720 < 1.4e-13 relative,
// while 1 - e^-k would lose ~log10(1/k) digits to cancellation. k = 0 (sigma_t = 0) gives dt.
SHARED_INLINE Real cloudStepIntegral(Real sigma_t, Real dt) {
  Real k = sigma_t * dt;
  if (k < 0.01) return dt * (1.0 - k * (1.0 / 2.0 - k * (1.0 / 6.0 - k * (1.0 / 24.0 - k * (1.0 / 120.0)))));
  return (1.0 - exp(-k)) / sigma_t;
}

// Draine's phase function (Draine 2003, eq. 4), a Henyey-Greenstein lobe times (1 + alpha nu^2):
//     p_D(nu; g, alpha) = p_HG(g, nu) (1 + alpha nu^2) / (1 + alpha (1 + 2 g^2) / 3),
// normalised (the HG lobe's second moment is (1 + 2 g^2) / 3). alpha = 0 gives p_HG(g, nu) exactly.
SHARED_INLINE Real drainePhase(Real g, Real alpha, Real nu) {
  return henyeyGreensteinPhase(g, nu) * (1.0 + alpha * nu * nu) / (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0);
}

// The phase function of cloud droplets: two lobes, p(nu) = (1 - w) p_HG(g1, nu) + w p_D(nu; g2, alpha)
// (normalised, 1/sr). Two models fill it (clouds/cloud_settings.h, CloudPhaseModel):
//   - dual Henyey-Greenstein (Hillaire 2016; default): g1 = g forward, g2 = g back, w = back weight,
//     alpha = 0;
//   - Jendersie and d'Eon 2023's approximate Mie phase of water droplets of diameter d (5-50 um):
//     HG plus Draine with g1 = g_HG(d), g2 = g_D(d), w = w_D(d), alpha = alpha(d) (cloudApproximateMie).
SHARED_INLINE Real cloudPhase(Real g1, Real g2, Real w, Real alpha, Real nu) {
  return mix(henyeyGreensteinPhase(g1, nu), drainePhase(g2, alpha, nu), w);
}

// The mean cosine <nu> of cloudPhase: (1 - w) g1 + w <nu>_D, with Draine's (Draine 2003, eq. 6)
//     <nu>_D = g (1 + alpha (3 + 2 g^2) / 5) / (1 + alpha (1 + 2 g^2) / 3).
SHARED_INLINE Real cloudPhaseMeanCosine(Real g1, Real g2, Real w, Real alpha) {
  Real draine = g2 * (1.0 + alpha * (3.0 + 2.0 * g2 * g2) / 5.0) / (1.0 + alpha * (1.0 + 2.0 * g2 * g2) / 3.0);
  return mix(g1, draine, w);
}

// Jendersie and d'Eon 2023, "An Approximate Mie Scattering Function for Fog and Cloud Rendering"
// (SIGGRAPH 2023 Talks), their fits for droplet diameters 5 <= d <= 50 um (d in um):
//   g_HG = exp(-0.0990567 / (d - 1.67154)),       g_D = exp(-2.20679 / (d + 3.91029) - 0.428934),
//   alpha = exp(3.62489 - 8.29288 / (d + 5.52825)), w_D = exp(-0.599085 / (d - 0.641583) - 0.665888).
// Returns (g1, g2, w, alpha) for cloudPhase.
SHARED_INLINE vec4 cloudApproximateMie(Real d) {
  return vec4(exp(-0.0990567 / (d - 1.67154)), exp(-2.20679 / (d + 3.91029) - 0.428934),
              exp(-0.599085 / (d - 0.641583) - 0.665888), exp(3.62489 - 8.29288 / (d + 5.52825)));
}

// Octave i of the multiple-scattering approximation (Wrenninge et al. 2013, "Oz: the great and
// volumetric"; Hillaire 2016): the light of octave i is that of single scattering with
// extinction scaled by a^i (longer free paths), intensity by b^i and phase eccentricity by c^i:
//     L_ms = Σ_{i=0}^{N-1} b^i σ_s p(c^i g, nu) E_sun T_atm e^(-a^i τ_sun).
// Energy: the octaves sum to at most Σ b^i times single scattering; with a <= b the added light never
// exceeds what the extinction removed (Hillaire 2016). The caller enforces a <= b.
// x^i by repeated products, with 0^0 = 1: GLSL leaves pow(x, y) undefined for x = 0 and y <= 0, and
// NVIDIA's pow(0, 0) = exp2(0 * log2 0) is NaN. The stratus fit has c = 0, so octave 0's
// c^0 turned every stratus pixel into NaN on an H100 while lavapipe gave 1 (docs/gpu.md).
SHARED_INLINE Real cloudOctavePower(Real x, int octave) {
  Real p = 1.0;
  for (int i = 0; i < octave; ++i) p *= x;
  return p;
}
SHARED_INLINE Real cloudOctaveWeight(Real b, int octave) { return cloudOctavePower(b, octave); }

// The factor on the weights b^i of octaves i >= 1 for N octaves: the three-octave total b + b^2 over
// the N-octave total sum_{i=1}^{N-1} b^i, so that N sets how the multiple-scattering light is spread
// over extinction scales a^i, not how much of it there is. Why: every fit has b at or near 1
// (docs/clouds.md, "Calibration"; 1 is the fit's upper bound), so each octave beyond the three the
// constants were fitted for added nearly another octave's light: 8 octaves gave 1.7x the light of 3
// on a stratocumulus deck at sunset and 7.5x on a thick cumulus, and the scene allows up to 8. With
// this factor 1.07x and 2.4x (test CloudOctaves.MoreOctavesAddLittleLight; the rest is the high
// octaves' vanishing extinction a^i). 1 at N = 3 exactly (x / x), and for N <= 1 or b = 0.
SHARED_INLINE Real cloudOctaveWeightScale(Real b, int octaves) {
  Real total = 0.0;
  for (int i = 1; i < octaves; ++i) total += cloudOctavePower(b, i);
  Real fitted = b + b * b;
  return total > 0.0 ? fitted / total : 1.0;
}
SHARED_INLINE Real cloudOctaveExtinctionScale(Real a, int octave) { return cloudOctavePower(a, octave); }
SHARED_INLINE Real cloudOctaveEccentricityScale(Real c, int octave) { return cloudOctavePower(c, octave); }

// The attenuation of octave i >= 1 at optical depth tau along a way in (docs/clouds.md, "Multiple
// scattering"). Wrenninge et al.'s octave uses e^(-a^i tau). With `scatteredOnly` the unscattered part
// e^(-tau) is taken out: light that has scattered at least once before reaching the sample is what
// reached it through the medium at the reduced rate a^i (a similarity-like extinction, cf. the
// (1 - g) sigma_t of the similarity relations) minus what came straight through. It is 0 at tau = 0 —
// thin wisps and edges get no multiple scattering, as in the path tracer — and e^(-a^i tau) deep inside
// (Schneider 2015's "powder" darkening of edges plays the same role as a multiplicative factor). Never
// above e^(-a^i tau), so the octaves' energy bound (a <= b) still holds.
SHARED_INLINE Real cloudOctaveTransmittance(Real extinctionScale, Real tau, bool scatteredOnly) {
  Real t = exp(-extinctionScale * tau);
  return scatteredOnly ? max(t - exp(-tau), 0.0) : t;
}

// The flux out of the base of a conservatively scattering slab of vertical optical depth tauVertical,
// direct and diffuse, per unit flux mu E on its top, sun at mu = cos(zenith) > 0 (clamped by the
// callers), phase asymmetry g: the two-stream (Eddington) solution's K / A, derived with
// cloudEddingtonSlabSource below (which uses it):
//   T = [(2/3 + mu) + (2/3 - mu) e^(-tauVertical/mu)] / (4/3 + (1 - g) tauVertical).
// 1 at tauVertical = 0; it falls as 1/tau, not exponentially, for a thick slab.
SHARED_INLINE Real cloudEddingtonTransmission(Real mu, Real tauVertical, Real g) {
  return ((2.0 / 3.0 + mu) + (2.0 / 3.0 - mu) * exp(-tauVertical / mu)) / (4.0 / 3.0 + (1.0 - g) * tauVertical);
}


// The most octave i can pass along any way in: the largest cloudOctaveTransmittance(s, tau) over
// tau >= 0. For e^(-s tau) it is 1 (tau = 0). For the scattered part e^(-s tau) - e^(-tau) with
// 0 < s < 1 the derivative -s e^(-s tau) + e^(-tau) vanishes at tau* = -ln(s) / (1 - s), the maximum;
// s <= 0 tends to 1 (tau -> inf) and s >= 1 gives 0. The march uses it to skip the way down from the
// layer top where that way cannot beat the sun ray for any optical depth (the result is unchanged).
SHARED_INLINE Real cloudOctaveTransmittanceBound(Real extinctionScale, bool scatteredOnly) {
  if (!scatteredOnly || extinctionScale <= 0.0) return 1.0;
  if (extinctionScale >= 1.0) return 0.0;
  Real tauStar = -log(extinctionScale) / (1.0 - extinctionScale);
  return exp(-extinctionScale * tauStar) - exp(-tauStar);
}

// The length of the light march from p (inside the layer's shell) towards the sun: the distance along
// the sun ray to where it leaves the shell (through the top, or the base for a sun below the local
// horizontal), at most maxLength. A sun at zenith angle theta crosses a layer of thickness H over
// about H / cos(theta) (11.5 km for 1 km at 85 deg): a march over a fixed length of one thickness saw
// a ninth of the optical depth at sunset (docs/clouds.md, "Lighting").
SHARED_INLINE Real cloudSunExitDistance(CloudLayer layer, vec3 p, vec3 sun, Real maxLength) {
  Real r = length(p);
  Real mu = clamp(dot(p, sun) / r, -1.0, 1.0);
  vec2 first;
  vec2 second;
  cloudShellSegments(r, mu, layer.bottom_radius, layer.top_radius, maxLength, first, second);
  // p is inside: the stretch that starts at p is `first` when the sun ray is headed for the base
  // (the inner sphere ahead), else `second` (the inner sphere's roots lie behind p, first is empty).
  if (first.x <= 0.0 && first.y > 0.0) return first.y;
  if (second.x <= 0.0) return max(second.y, 0.0);
  return 0.0;
}

// The escape function of a thick conservatively scattering layer: the angular factor of the light
// that diffuses through it, per unit flux mu0 E entering at mu0 = cos(zenith) (and, by reciprocity, of
// the light leaving at mu0), normalised by 2 integral K mu dmu = 1. For isotropic scattering it is
// K(mu) = (sqrt 3 / 4) H(mu) with Chandrasekhar's H function for albedo 1 (Chandrasekhar 1960; van de
// Hulst 1980: the thick layer's transmission is T(mu0) ~ K(mu0) / (3/4 (1 - g) tau + 1.07)), and the
// similarity relations carry it over to forward-scattering clouds. H is fitted here as 1 + 1.6436 mu +
// 0.2679 sqrt(mu) (least squares in relative error over mu in (0, 1]: at most 0.9 % from H, which the
// tests CloudEscape.* solve in double). The Eddington approximation's factor is 1/2 + 3/4 mu0 (Joseph,
// Wiscombe and Weinman 1976), 15 % too large at the horizon and 7 % at mu0 = 0.087 (the sun 85 deg from
// the zenith): a sun near the horizon sent too much light down through a deck.
SHARED_INLINE Real cloudEscapeFunction(Real mu) {
  Real m = clamp(mu, 0.0, 1.0);
  return 0.4330127 * (1.0 + 1.6436 * m + 0.2679 * sqrt(m));
}

// The factor that turns the Eddington angular dependence into the escape function's, K(mu0) / (1/2 +
// 3/4 mu0): 0.936 at mu0 = 0.087, 0.995 at 0.5, 1.009 at 1. The diffusion floor (cloudEddingtonSlabSource,
// an Eddington solution) is scaled by it; its depth dependence stays the two-stream one.
SHARED_INLINE Real cloudEscapeCorrection(Real mu0) {
  Real m = clamp(mu0, 0.0, 1.0);
  return cloudEscapeFunction(m) / (0.5 + 0.75 * m);
}

// The floor's factor for a low sun with a forward-peaked phase: light entering a thick layer at a grazing
// angle and scattered mostly forwards turns back out of the top more often than the isotropic escape
// function (cloudEscapeFunction; the similarity relations carry it over for the flux at moderate angles
// only) says. Against the project's photon Monte Carlo of a homogeneous conservative slab with the
// default phase (clouds/slab_monte_carlo.h; `bench_floor_slab`, 2 million photons per case, optical
// thickness 10, 20, 40; the light of orders >= 2 leaving the base at mu >= 0.1) the floor was 9-10 % too
// bright at mu0 = 0.087, 5.5-6 % at 0.15, 3-5 % at 0.2, 1-2.5 % at 0.3, within 1 % from 0.45 up. Fitted to
// that sweep: 1 - 0.178 e^(-mu0 / 0.125) (0.911 at 0.087, 0.946 at 0.15, 0.984 at 0.3, 0.999 at 0.64;
// all 21 cases 0.988-1.008 after it; test CloudFloorAgainstMonteCarlo.LowSunFactorCorrectsTheGrazingEntry;
// docs/clouds.md "Lighting", item 6).
SHARED_INLINE Real cloudFloorLowSunFactor(Real mu0) {
  return 1.0 - 0.178 * exp(-max(mu0, 0.0) / 0.125);
}

// The octaves' (i >= 1) and the reflected light's low-sun scale min(1, mu_s / mu_0) (mu_0 <= 0: off, 1).
// Measured, not derived: in broken cumulus fields under a low sun the octaves, fitted under higher suns,
// give up to three times the path tracer's higher orders, nearly uniformly over the image (docs/clouds.md "Lighting", the low sun),
// while the single scattering is within ~10 % (the deep shadow map's, docs/clouds.md "The deep shadow map"). mu_0 is fitted per cloud type on calibration scenes with suns at
// 76-85 deg (the `--low-sun` fit of `bench clouds --calibrate`).
SHARED_INLINE Real cloudOctaveLowSunScale(Real muS, Real mu0) {
  return mu0 > 0.0 ? min(1.0, max(muS, 0.0) / mu0) : 1.0;
}

// The floor's two corrections for the sun's angle, together: the escape function's angular factor
// (cloudEscapeCorrection) times the low-sun factor (cloudFloorLowSunFactor). The march's floor and the
// deck's transmission (cloudSlabTransmission) both take it.
SHARED_INLINE Real cloudFloorSunFactor(Real mu0) {
  return cloudEscapeCorrection(mu0) * cloudFloorLowSunFactor(mu0);
}

// The flux out of the base of a deck crossed along the sun over optical depth tauSlant (vertical depth
// mu0 tauSlant), per unit flux mu0 E on its top: the direct beam e^(-tauSlant) plus the diffuse part of
// cloudEddingtonTransmission (mu0 clamped at 0.02 as the floor clamps it; the form clamped to 1: for
// mu0 g > 2/3 it rises above 1 at small depths, outside its validity) times the floor's two corrections,
// the escape function's angular factor and the low-sun factor (capped at 1, which keeps T falling with
// depth; above 1 only for mu0 > 0.6, by at most 0.9 %). Why: against the project's photon Monte Carlo of a
// conservative slab with the default phase (clouds/slab_monte_carlo.h, 200 000 photons per case, vertical
// optical depth 1-40, mu0 0.087-1) the Eddington diffuse part alone was 15-22 % too large at mu0 = 0.087
// and 9-13 % at 0.15; with the corrections all 36 cases are 0.978-1.077 of it, those at mu0 <= 0.5
// 0.978-1.037 (the largest left, +7.7 % at depth 1 and +4.5 % at 2 under a zenith sun, is the
// Eddington form's own; test CloudDeckTransmission.MatchesTheSlabMonteCarlo; docs/clouds.md
// "Lighting", item 6).
SHARED_INLINE Real cloudSlabTransmission(Real tauSlant, Real mu0, Real g) {
  Real m = max(mu0, 0.02);
  Real tau = max(tauSlant, 0.0);
  Real eddington = min(cloudEddingtonTransmission(m, m * tau, g), 1.0);
  Real direct = exp(-tau);
  Real correction = min(cloudFloorSunFactor(m), 1.0);
  return direct + correction * max(eddington - direct, 0.0);
}

// The light a sample scatters from a deck above it, per unit solar irradiance and in units of the
// isotropic phase 1/4pi: the deck passes the flux T mu0 E (cloudSlabTransmission T, optical depth
// tauOther along the sun), which leaves its base as radiance of about T mu0 E / pi over the upper
// hemisphere, and a sample scatters (1/4pi) 2pi T mu0 E / pi = 2 mu0 T E / 4pi of it. 0 for a sun at or
// below the horizon.
SHARED_INLINE Real cloudDeckDiffuseLight(Real tauOther, Real mu0, Real g) {
  return 2.0 * max(mu0, 0.0) * cloudSlabTransmission(tauOther, mu0, g);
}

// The attenuation of octave i >= 1 when the sun's light crosses other layers first (optical depth
// tauOther along the sun) and then the sample's own layer (tauOwn). The octave alone would take
// e^(-a^i (tauOwn + tauOther)): for a thick deck above it goes to 0 exponentially, where the deck
// passes ~1/tau of the flux, scattered (the bench's two_layers: a cumulus fit with a larger a left the
// cumulus under the deck -21 %). The octaves i >= 1 together (their phases ~1/4pi for light
// from all over the sky) carry at least the deck's diffuse light D = cloudDeckDiffuseLight, octave i
// its share b^i / sum_j b^j (share). So the way through the others is the octave's own
// e^(-a^i tauOther), but at least share D, and from the deck's base on the octave is attenuated by the
// own layer as before. With tauOther = 0 (D <= 2, the first term 1) it is cloudOctaveTransmittance(a^i,
// tauOwn) exactly.
SHARED_INLINE Real cloudOctaveTransmittanceThroughOthers(Real extinctionScale, Real tauOwn, Real tauOther, Real deckLight, Real share,
                                                         bool scatteredOnly) {
  Real through = max(exp(-extinctionScale * tauOther), min(share * deckLight, 1.0));
  Real t = through * exp(-extinctionScale * tauOwn);
  return scatteredOnly ? max(t - exp(-(tauOwn + tauOther)), 0.0) : t;
}

// The weight of the way down from a layer's top for octaves i >= 1 (docs/clouds.md, "Multiple
// scattering"): sunlight entering a horizontal top at mu_s = cos(sun zenith) brings the flux E mu_s,
// and the part of it that diffuses down through a thick, conservatively scattering slab grows like the
// escape function K(mu_s) (cloudEscapeFunction; rather than the Eddington approximation's 1/2 +
// 3/4 mu_s): light entering at a grazing angle is turned back out of the top before it gets deep. Normalised
// to 1 for the sun at the zenith: mu_s K(mu_s) / K(1); 0 for the sun at or below the horizontal.
SHARED_INLINE Real cloudTopEntryWeight(Real muS) {
  Real m = clamp(muS, 0.0, 1.0);
  return m * cloudEscapeFunction(m) / cloudEscapeFunction(1.0);
}

// The diffuse light inside a conservatively scattering slab lit from above, per unit solar irradiance
// E (normal to the beam) and per steradian: the mean intensity I0 of the Eddington approximation
// (Shettle and Weinman 1970), at optical depth tau below the top of a slab of optical thickness
// tauTotal, sun at mu0 = cos(zenith) > 0, phase asymmetry g. Derivation (tau downwards, I = I0 + mu I1,
// P = 1 + 3 g mu mu', direct beam E e^(-tau/mu0)); the zeroth and first moments of the transfer equation
// with omega = 1 give
//   dI1/dtau = 3 E e^(-tau/mu0) / 4pi,   dI0/dtau = -(1 - g) I1 + 3 g mu0 E e^(-tau/mu0) / 4pi,
// so with A = 3 mu0 E / 4pi: I1 = K - A e^(-tau/mu0) and I0 = M - (1 - g) K tau - A mu0 e^(-tau/mu0).
// No diffuse light enters at the top (I0 + 2/3 I1 = 0 at 0) or from a black ground below
// (I0 - 2/3 I1 = 0 at tauTotal):
//   K = A [(2/3 + mu0) + (2/3 - mu0) e^(-tauTotal/mu0)] / (4/3 + (1 - g) tauTotal)   (K / A ~ transmission)
//   I0(tau) = A [(mu0 + 2/3) - mu0 e^(-tau/mu0)] - K [2/3 + (1 - g) tau].
// The light this diffuse field scatters into a direction whose cosine with the downward vertical is
// muDown is (omega / 4pi) integral of P I = I0 + g muDown I1 (the phase's first moment): seen from below,
// the base of a deck sends down more than I0 (at the base I1 = 3/2 I0).
// I0 falls linearly with depth (diffusion) where the exponential octaves fall exponentially: the base of
// a thick deck under a high sun is lit by it (docs/clouds.md, "Multiple scattering"). It is 0 for a
// vanishing slab and at most ~2 mu0 E / 4pi at the top of a thick one; clamped at 0 against rounding.
SHARED_INLINE Real cloudEddingtonSlabSource(Real mu0, Real tau, Real tauTotal, Real g, Real muDown) {
  if (mu0 <= 0.0) return 0.0;
  Real m = max(mu0, 0.02);  // e^(-tau/mu0) is then 0 for any real depth; keeps the division finite
  Real a = 3.0 * m / (4.0 * kPi);
  Real s = 1.0 - g;
  Real k = a * cloudEddingtonTransmission(m, tauTotal, g);
  Real beam = exp(-tau / m);
  Real i0 = a * ((m + 2.0 / 3.0) - m * beam) - k * (2.0 / 3.0 + s * tau);
  Real i1 = k - a * beam;
  return max(i0 + g * muDown * i1, 0.0) * min(mu0 / m, 1.0);
}

// The diffusion floor's limb darkening at a layer's base: the factor on cloudEddingtonSlabSource for
// light scattered down towards a viewer below, at muDown = cos(angle from the downward vertical) > 0,
// vertical optical depth tauBelow above the base and transmittance viewTransmittance to the viewer. The
// Eddington source makes the radiance leaving a thick slab's base go like 2/3 + mu, which is too bright
// at grazing exits: against the project's Monte Carlo of a homogeneous conservative slab with the
// default phase (clouds/slab_monte_carlo.h; `bench_floor_slab`, optical thickness 10 and 20, sun at mu0
// 0.3 to 1) 0 to +8 % at mu = 0.25, +5 to +20 % at 0.15, +19 to +30 % at 0.05, and 0.98 to 1.07 of it for
// mu >= 0.35 (standard errors 1-3 %). The exact source falls towards the boundary within ~mu of it
// (grazing light leaves from the boundary layer), so it is lowered there: 1 - beta(mu) e^(-tauBelow / mu)
// with beta = 0.6 e^(-mu / 0.15), fitted to that Monte Carlo (the radiance leaving the base then 0.94 to
// 1.07 of it for every mu >= 0.05; test CloudFloorAgainstMonteCarlo.BaseLimbDarkeningCorrectsGrazingExits;
// docs/clouds.md "Lighting", item 6). A sample whose way to the viewer is longer than its slant way to the base
// (optical depth tauView > tauBelow / mu: seen through a cloud's side, not its base) keeps more of the
// source: the exponent takes the larger, e^(-max(tauBelow / mu, tauView)) = min(e^(-tauBelow / mu),
// viewTransmittance), so the march passes the transmittance it has. `strength` scales beta (cloudTypeBaseLimbDarkening: 1 for stratus and
// stratocumulus, the layers that are slabs; 0 for the others: a finite cumulus's bases are not a slab's,
// and cirrus held out worse with it). 1 for light
// scattered upwards (the top's reflection, which the octaves and cloudReflectedSource carry).
SHARED_INLINE Real cloudBaseLimbFactor(Real muDown, Real tauBelow, Real viewTransmittance, Real strength) {
  if (!(muDown > 0.0) || !(strength > 0.0)) return 1.0;
  Real m = max(muDown, 1e-3);
  return 1.0 - strength * 0.6 * exp(-m / 0.15) * min(exp(-max(tauBelow, 0.0) / m), clamp(viewTransmittance, 0.0, 1.0));
}

// A conservative slab's transmission of diffuse light, T = (4/3) / (4/3 + tau') (two-stream Eddington
// with Marshak's boundaries, tau' the similarity-scaled optical depth), its reflectance 1 - T =
// tau' / (4/3 + tau') (written so, exact as tau' -> 0: cloudReflectedSource), and the inverse of T: the
// depth of the uniform slab that transmits T. The ambient's view of a broken layer
// (bake_column_ambient.comp) averages T over columns and takes the depth back.
SHARED_INLINE Real cloudDiffuseSlabTransmission(Real tauScaled) { return (4.0 / 3.0) / (4.0 / 3.0 + max(tauScaled, 0.0)); }
SHARED_INLINE Real cloudDiffuseSlabReflectance(Real tauScaled) { return max(tauScaled, 0.0) / (4.0 / 3.0 + max(tauScaled, 0.0)); }
SHARED_INLINE Real cloudDiffuseSlabDepth(Real transmission) { return (4.0 / 3.0) * (1.0 / max(transmission, 1e-6) - 1.0); }

// The light that the cloud behind a sample (further from the sun along the sun's line) turns back
// towards the sun, as a source for octaves i >= 1, per unit solar irradiance and per steradian
// (docs/clouds.md, "Multiple scattering"). The octaves carry light on along the sun's direction
// (transmission); a sunlit face of a thick cloud seen with the sun behind the camera is bright with
// light reflected by the cloud under it, which they lack (that quarter of the noon pixels
// -21 % without the diffusion floor). Three factors:
//   - the reflectance of the medium behind, optical depth tauBehind along the sun: s tau / (4/3 + s tau)
//     with s = 1 - g (cloudDiffuseSlabReflectance), the diffuse reflectance of a conservative slab in the two-stream (Eddington) form
//     1 - T, T = (4/3) / (4/3 + (1 - g) tau) (Shettle and Weinman 1970): 0 for a thin wisp, towards 1
//     for a deep cloud;
//   - exp(-depthScale tauSun): the sunlight reaching the reflecting medium and the reflected light
//     coming back to the sample both cross the sample's depth from the sun;
//   - the angular lobe (1 - nu) / 4pi (normalised; nu = view . sun): reflected light travels back towards
//     the sun, so a camera with the sun behind it (nu -> -1) sees it scattered forward, a camera looking
//     towards the sun sees little of it.
SHARED_INLINE Real cloudReflectedSource(Real tauBehind, Real tauSun, Real g, Real depthScale, Real nu) {
  return cloudDiffuseSlabReflectance((1.0 - g) * max(tauBehind, 0.0)) * exp(-depthScale * max(tauSun, 0.0)) * (1.0 - nu) / (4.0 * kPi);
}

// The reflected light's depth scale under the low-sun scale s = cloudOctaveLowSunScale (1 above mu_0):
// a_r / s, so e^(-a_r tau_sun / s). Measured, not derived: a_r was fitted under suns whose line crosses
// about one cloud; under a low sun it crosses kilometres of broken field, and with a_r alone the light
// reflected from deep along it stayed bright (in the calibration's view away from a sun 82 deg
// from the zenith, +26 % over the image and 2.1x on the far cloud bases, the reflected light more than
// half the model's light there). Refitting a_r itself for every sun did as well on the low-sun scenes but
// worse on the held-out views from above; this leaves suns above mu_0 exactly as they were.
// s is clamped at 1e-3 (the sun at the horizon: the term is then ~0, as the scale makes it anyway).
SHARED_INLINE Real cloudReflectedLowSunDepthScale(Real depthScale, Real lowSunScale) {
  return depthScale / max(lowSunScale, 1e-3);
}

// The higher orders' build-up along the view ray (docs/clouds.md, "Build-up along the view"). The
// octaves and the floor give a sample p a source of orders >= 2 from the sun's side of p only. But the
// light of orders >= 2 that p sends towards the camera was mostly travelling nearly that way already
// (the phase's forward lobe), and that light builds up over the cloud behind p along the view ray: a
// sample at the far side of a thin cloud, or at the back of a wisp, has little behind it. So the march
// weights that source by 1 - e^(-k tau_behind), tau_behind the view ray's optical depth behind p (from
// p to where the ray leaves the cloud), k the scale CloudMarchSettings::msBuildUpScale. Through a
// homogeneous cloud of optical depth tau with a uniform source J the light is then
//   J [(1 - e^-tau) - (e^-tau - e^(-k tau)) / (k - 1)]  (k != 1),
// about J k tau^2 / 2 for tau << 1 (second order grows as tau^2, not tau) and J for tau -> infinity.
// tau_behind is known only once the march has left the cloud, so the march keeps the weighted sum
// R = sum_i c_i e^(-k (tau_now - tau_i)) of the steps' light of orders >= 2 c_i (tau_i at the middle of
// step i, tau_now where the march is) and takes R off the light at the end. Each step multiplies R by
// cloudBuildUpDecay(k, dTau) and adds c_i cloudBuildUpStepWeight(k, dTau): every factor is at most 1,
// so R stays between 0 and the sum of the c_i at any optical depth (no exponential of a growing tau).
// A march that stops at its early exit takes the rest of the ray as opaque: tau_behind infinite, R not
// taken off.
SHARED_INLINE Real cloudBuildUpDecay(Real k, Real dTau) { return exp(-k * max(dTau, 0.0)); }
SHARED_INLINE Real cloudBuildUpStepWeight(Real k, Real dTau) { return exp(-0.5 * k * max(dTau, 0.0)); }

// The ground's share w of the ambient's mean radiance J = (1 - w) L_sky + w L_ground at a point of a
// conservative slab lit from above by a uniform sky L_sky and from below by a uniform ground L_ground,
// at optical depth tau_up below its top and tau_down above its base. Eddington's approximation with
// the Marshak boundary conditions makes J linear in the optical depth between the extrapolated
// boundaries 2/3 outside each face, where it reaches L_sky and L_ground:
//     w = (tau_up + 2/3) / (tau_up + tau_down + 4/3).
// Thin (tau -> 0): w = 1/2, the single scattering of the unobstructed field. Thick: the top sees the
// sky, the base the ground. For a uniform field (L_sky = L_ground = L) J = L at every depth: a
// non-absorbing cloud in uniform light is in equilibrium, whatever its optical depth. The depths are
// the similarity-scaled ones, (1 - g) tau, for an anisotropic phase (van de Hulst 1980).
SHARED_INLINE Real cloudAmbientGroundWeight(Real tauUp, Real tauDown) {
  return (max(tauUp, 0.0) + 2.0 / 3.0) / (max(tauUp, 0.0) + max(tauDown, 0.0) + 4.0 / 3.0);
}

// The ground's share w' of the ambient light a sample scatters towards the camera, for a phase of mean
// cosine g: the slab's mean radiance J carries no direction, but the slab's light flows from the
// brighter side to the other, and a forward-scattering phase turns that flow on towards a camera it
// faces. In Eddington's approximation L(omega) = J + (3 / 4pi) F.omega, with the net flux
// F = -(4pi / 3) dJ/dtau' straight up (tau' the similarity-scaled depth; J linear in it between the
// extrapolated boundaries: F_up = (4pi / 3)(L_ground - L_sky) / (tau' + 4/3)). Light scattered into
// direction v gets S(v) = J + (3 / 4pi) g F.v. The light towards a camera looking along `dir` goes
// along v = -dir, so with mu_view = dir.up:
//     S = (1 - w') L_sky + w' L_ground,   w' = w - g mu_view / (tau'_up + tau'_down + 4/3),
// clamped to [0, 1] (the linear radiance overshoots for a thin cloud and a strongly forward phase).
// Looking up at a base (mu_view > 0) the sky behind the cloud shows through its forward lobe more
// than the ground below does; looking down at a top, the ground's light. A uniform field stays uniform.
SHARED_INLINE Real cloudAmbientViewGroundWeight(Real tauUp, Real tauDown, Real g, Real muView) {
  Real tau = max(tauUp, 0.0) + max(tauDown, 0.0);
  return clamp(cloudAmbientGroundWeight(tauUp, tauDown) - g * muView / (tau + 4.0 / 3.0), 0.0, 1.0);
}

// Ambient light on a cloud sample (docs/clouds.md, "Lighting"): isotropic scattering of a sky of uniform
// radiance L_sky = E_sky / pi over the upper hemisphere and a Lambertian ground of radiance L_ground
// over the lower one gives the in-scattered radiance (1/4pi)(2pi L_sky + 2pi L_ground) = (L_sky +
// L_ground) / 2 (the slab's w = 1/2). By height (CloudMarchSettings::ambientSlab false),
// the cloud hides part of each hemisphere: the sky is scaled by a visibility rising linearly from
// `bottomVisibility` at the base to 1 at the top of the shell, the ground by one falling from 1 at the
// base to `bottomVisibility` at the top (after Hillaire 2016's top/bottom ambient gradient). Their sum is
// 1 + bottomVisibility < 2, so a uniform field loses light in the cloud.
SHARED_INLINE Real cloudSkyVisibility(Real ph, Real bottomVisibility) { return mix(bottomVisibility, 1.0, clamp(ph, 0.0, 1.0)); }
SHARED_INLINE Real cloudGroundVisibility(Real ph, Real bottomVisibility) { return mix(1.0, bottomVisibility, clamp(ph, 0.0, 1.0)); }

SHARED_END

#endif  // FIRMAMENT_CLOUD_LIGHTING_GLSL
