#include "atmosphere/reference_single_scattering.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/atmosphere_lut.glsl"

namespace firmament::reference {
namespace {

// Absolute floor of the in-scattering error test, per metre of panel and per unit solar irradiance
// (sr^-1 m^-1): far below any sky radiance that matters (a deep-twilight sky is ~1e-8 E sr^-1,
// i.e. an integrand of ~1e-14 E sr^-1 m^-1 at sea level).
constexpr double kInScatteringFloor = 1e-22;
constexpr int kMaxPanelDepth = 48;

}  // namespace

SunDisc::SunDisc(double angularRadius)
    : angularRadius_(angularRadius), cosRadius_(std::cos(angularRadius)), sinRadius_(std::sin(angularRadius)) {
  // Omega_eff = ∫_disc mu^0.5 dOmega = 2 pi ∫_{cos alpha}^1 mu(c)^0.5 dc, c = cos theta, with
  //   mu^2 = 1 - sin^2 theta / sin^2 alpha = (c^2 - cos^2 alpha) / sin^2 alpha.
  // The integrand behaves like (c - cos alpha)^(1/4) at the limb; c = cos alpha + (1 - cos alpha) v^4
  // makes it smooth: c - cos alpha = k v^4 (k = 1 - cos alpha = 2 sin^2(alpha/2)), dc = 4 k v^3 dv,
  //   mu^2 = k v^4 (c + cos alpha) / sin^2 alpha,  mu^0.5 = v (k (c + cos alpha) / sin^2 alpha)^(1/4),
  //   Omega_eff = 2 pi ∫_0^1 v (k (c + cos alpha)/sin^2 alpha)^(1/4) 4 k v^3 dv,
  // a smooth integrand that K15 on 8 panels integrates to rounding.
  const double k = 2.0 * std::sin(0.5 * angularRadius) * std::sin(0.5 * angularRadius);
  const GaussKronrod15& rule = gaussKronrod15();
  double sum = 0.0;
  const int panels = 8;
  for (int p = 0; p < panels; ++p) {
    const double a = double(p) / panels, b = double(p + 1) / panels;
    for (int i = 0; i < kKronrodPoints; ++i) {
      const double v = 0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[i];
      const double c = cosRadius_ + k * v * v * v * v;
      const double muQuarter = v * std::pow(k * (c + cosRadius_) / (sinRadius_ * sinRadius_), 0.25);
      sum += 0.5 * (b - a) * rule.kronrodWeights[i] * muQuarter * 4.0 * k * v * v * v;
    }
  }
  effectiveSolidAngle_ = 2.0 * shared::kPi * sum;
}

double SunDisc::profile(double cosTheta, double sinTheta) const {
  if (cosTheta < cosRadius_ || !(effectiveSolidAngle_ > 0.0)) return 0.0;
  const double rho = std::min(sinTheta / sinRadius_, 1.0);
  const double mu = std::sqrt(std::max(1.0 - rho * rho, 0.0));
  return std::pow(mu, kLimbDarkeningExponent) / effectiveSolidAngle_;
}

SingleScatteringIntegrator::SingleScatteringIntegrator(const SpectralMedium& medium, glm::dvec3 sunDirection,
                                                       double relativeTolerance)
    : medium_(medium),
      sun_(glm::normalize(sunDirection)),
      relativeTolerance_(relativeTolerance),
      columns_(medium, relativeTolerance),
      sunDisc_(medium.sunAngularRadius()) {}

DeterministicRadiance SingleScatteringIntegrator::integrate(const ViewSegment& view, bool includeSunDisc,
                                                            bool includeSingleScattering) const {
  const int n = medium_.wavelengthCount();
  DeterministicRadiance result;
  result.sunDisc.assign(size_t(n), 0.0);
  result.singleScattering.assign(size_t(n), 0.0);
  const double nu = std::clamp(glm::dot(view.direction, sun_), -1.0, 1.0);

  ConstituentDensities column(0.0);
  if (view.inAtmosphere) {
    if (includeSingleScattering) {
      // Split the segment where it crosses the shadow's edge (the integrand jumps there), then
      // integrate each smooth piece adaptively, carrying the view column from piece to piece.
      // Also at the density breaks, where the integrand has kinks.
      std::vector<double> cuts =
          shadowCrossings(view.origin, view.direction, sun_, medium_.groundRadius(), view.segment.length);
      double densityCuts[ColumnIntegrator::kMaxCuts];
      const int densityCutCount = columns_.initialCuts(view.segment, densityCuts);
      cuts.insert(cuts.end(), densityCuts, densityCuts + densityCutCount);
      std::sort(cuts.begin(), cuts.end());
      const double phaseR = shared::rayleighPhase(nu);
      const double phaseM = shared::cornetteShanksPhase(medium_.miePhaseG(), nu);
      for (size_t k = 0; k + 1 < cuts.size(); ++k)
        if (cuts[k + 1] > cuts[k])
          integratePanel(view, cuts[k], cuts[k + 1], 0, phaseR, phaseM, &column, &result.singleScattering);
    } else {
      column = columns_.column(view.segment);
    }
  }
  result.viewColumn = column;

  if (includeSingleScattering && view.inAtmosphere && view.hitsGround) {
    // Ground: Lambertian, lit by the transmitted sun: L = T_view a/pi E mu_s T_sun.
    const glm::dvec3 ground = view.origin + view.direction * view.segment.length;
    const double muSun = glm::dot(glm::normalize(ground), sun_);
    ConstituentDensities sunColumn;
    if (muSun > 0.0 && columns_.columnToSun(medium_.groundRadius(), muSun, &sunColumn)) {
      for (int i = 0; i < n; ++i) {
        const double tau = glm::dot(medium_.extinctionPerDensity(i), column + sunColumn);
        result.singleScattering[size_t(i)] +=
            std::exp(-tau) * medium_.groundAlbedo(i) / shared::kPi * medium_.solarIrradiance(i) * muSun;
      }
    }
  }

  if (includeSunDisc && !view.hitsGround) {
    // Rays from space that miss the atmosphere also see the disc, unattenuated (column = 0). A ray
    // that meets the ground never sees it.
    const double sinTheta = glm::length(glm::cross(view.direction, sun_));
    const double profile = sunDisc_.profile(nu, sinTheta);
    if (profile > 0.0)
      for (int i = 0; i < n; ++i)
        result.sunDisc[size_t(i)] =
            std::exp(-glm::dot(medium_.extinctionPerDensity(i), column)) * medium_.solarIrradiance(i) * profile;
  }
  return result;
}

void SingleScatteringIntegrator::integratePanel(const ViewSegment& view, double a, double b, int depth,
                                                double rayleighPhase, double miePhase,
                                                ConstituentDensities* columnBefore,
                                                std::vector<double>* radiance) const {
  const GaussKronrod15& rule = gaussKronrod15();
  const int n = medium_.wavelengthCount();
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  const double originDotSun = glm::dot(view.origin, sun_);
  const double directionDotSun = glm::dot(view.direction, sun_);

  // Densities at the 15 nodes, the column from the segment start to each node (the panel's
  // cumulative matrix, reference_quadrature.h), and the column toward the sun from each node.
  ConstituentDensities densities[kKronrodPoints];
  for (int k = 0; k < kKronrodPoints; ++k)
    densities[k] = medium_.densitiesAt(view.segment.radiusAt(centre + half * rule.nodes[k]));
  ConstituentDensities panelK(0.0), panelG(0.0);
  for (int k = 0; k < kKronrodPoints; ++k) {
    panelK += rule.kronrodWeights[k] * densities[k];
    panelG += rule.gaussWeights[k] * densities[k];
  }
  panelK *= half;
  panelG *= half;

  std::vector<double> kronrod(size_t(n), 0.0), gauss(size_t(n), 0.0);
  for (int i = 0; i < kKronrodPoints; ++i) {
    const double t = centre + half * rule.nodes[i];
    ConstituentDensities toNode(0.0);
    for (int k = 0; k < kKronrodPoints; ++k) toNode += rule.cumulative[i][k] * densities[k];
    const ConstituentDensities viewColumn = *columnBefore + half * toNode;
    const double r = view.segment.radiusAt(t);
    const double muSun = (originDotSun + t * directionDotSun) / r;
    ConstituentDensities sunColumn;
    if (!columns_.columnToSun(r, muSun, &sunColumn)) continue;  // in the planet's shadow
    const ConstituentDensities& d = densities[i];
    for (int w = 0; w < n; ++w) {
      // T_view T_sun = exp(-beta . (D_view + D_sun)); in-scattering sigma_R p_R + sigma_M p_CS.
      const double transmittance = std::exp(-glm::dot(medium_.extinctionPerDensity(w), viewColumn + sunColumn));
      const double scattering =
          medium_.rayleighScattering(w) * d.x * rayleighPhase + medium_.mieScattering(w) * d.y * miePhase;
      const double f = transmittance * scattering * medium_.solarIrradiance(w);
      kronrod[size_t(w)] += rule.kronrodWeights[i] * f;
      gauss[size_t(w)] += rule.gaussWeights[i] * f;
    }
  }

  bool accepted = depth >= kMaxPanelDepth;
  if (!accepted) {
    accepted = true;
    const glm::dvec3 scale = medium_.maxExtinctionPerDensity();
    for (int c = 0; c < 3 && accepted; ++c)
      if (scale[c] > 0.0 && std::abs(panelK[c] - panelG[c]) >
                                relativeTolerance_ * panelK[c] + ColumnIntegrator::kOpticalDepthFloor / scale[c])
        accepted = false;
    for (int w = 0; w < n && accepted; ++w) {
      const double k = half * kronrod[size_t(w)], g = half * gauss[size_t(w)];
      if (std::abs(k - g) > relativeTolerance_ * k + kInScatteringFloor * medium_.solarIrradiance(w) * (b - a))
        accepted = false;
    }
  }
  if (accepted) {
    for (int w = 0; w < n; ++w) (*radiance)[size_t(w)] += half * kronrod[size_t(w)];
    *columnBefore += panelK;
    return;
  }
  integratePanel(view, a, centre, depth + 1, rayleighPhase, miePhase, columnBefore, radiance);
  integratePanel(view, centre, b, depth + 1, rayleighPhase, miePhase, columnBefore, radiance);
}

}  // namespace firmament::reference
