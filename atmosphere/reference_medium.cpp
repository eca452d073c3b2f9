#include "atmosphere/reference_medium.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace firmament::reference {
namespace {

bool sameLayer(const shared::DensityLayer& a, const shared::DensityLayer& b) {
  return a.width == b.width && a.exp_term == b.exp_term && a.exp_scale == b.exp_scale &&
         a.linear_term == b.linear_term && a.constant_term == b.constant_term;
}

bool sameProfile(const shared::DensityProfile& a, const shared::DensityProfile& b) {
  return sameLayer(a.layer0, b.layer0) && sameLayer(a.layer1, b.layer1);
}

// Altitudes where a layer's unclamped value exp_term e^(exp_scale h) + linear_term h + constant_term
// reaches 0 or 1 (the clamp makes a kink there), for the forms that have a closed form: linear
// (exp_term = 0) and pure exponential (linear_term = constant_term = 0).
void addClampAltitudes(const shared::DensityLayer& layer, std::vector<double>* altitudes) {
  for (double level : {0.0, 1.0}) {
    if (layer.exp_term == 0.0 && layer.linear_term != 0.0) {
      altitudes->push_back((level - layer.constant_term) / layer.linear_term);
    } else if (layer.linear_term == 0.0 && layer.constant_term == 0.0 && layer.exp_term > 0.0 &&
               layer.exp_scale != 0.0 && level > 0.0) {
      altitudes->push_back(std::log(level / layer.exp_term) / layer.exp_scale);
    }
  }
}

}  // namespace

std::vector<double> evenlySpacedWavelengths(int count) {
  if (count < 1) throw std::invalid_argument("evenlySpacedWavelengths: count must be >= 1");
  if (count == 1) return {555.0};
  std::vector<double> wavelengths(static_cast<size_t>(count), 0.0);
  for (int i = 0; i < count; ++i) wavelengths[size_t(i)] = 360.0 + (830.0 - 360.0) * double(i) / double(count - 1);
  return wavelengths;
}

SpectralMedium SpectralMedium::fromSettings(const AtmosphereSettings& settings,
                                            const std::vector<double>& wavelengthsNm) {
  std::vector<shared::AtmosphereParameters> triples;
  for (size_t first = 0; first < wavelengthsNm.size(); first += 3) {
    glm::dvec3 triple;
    for (size_t c = 0; c < 3; ++c) triple[int(c)] = wavelengthsNm[std::min(first + c, wavelengthsNm.size() - 1)];
    triples.push_back(atmosphereParametersAt(settings, triple));
  }
  return fromParameters(triples, wavelengthsNm);
}

SpectralMedium SpectralMedium::fromParameters(const std::vector<shared::AtmosphereParameters>& triples,
                                              const std::vector<double>& wavelengthsNm) {
  if (wavelengthsNm.empty()) throw std::invalid_argument("SpectralMedium: no wavelengths");
  if (triples.size() != (wavelengthsNm.size() + 2) / 3)
    throw std::invalid_argument("SpectralMedium: need one parameter set per triple of wavelengths");
  SpectralMedium m;
  m.wavelengths_ = wavelengthsNm;
  m.geometry_ = triples.front();
  for (const auto& t : triples) {
    if (t.bottom_radius != m.geometry_.bottom_radius || t.top_radius != m.geometry_.top_radius ||
        t.mie_phase_g != m.geometry_.mie_phase_g || t.sun_angular_radius != m.geometry_.sun_angular_radius ||
        !sameProfile(t.rayleigh_density, m.geometry_.rayleigh_density) ||
        !sameProfile(t.mie_density, m.geometry_.mie_density) ||
        !sameProfile(t.absorption_density, m.geometry_.absorption_density))
      throw std::invalid_argument("SpectralMedium: wavelength-independent fields differ between triples");
  }
  if (!(m.geometry_.top_radius > m.geometry_.bottom_radius) || !(m.geometry_.bottom_radius > 0.0))
    throw std::invalid_argument("SpectralMedium: need 0 < ground radius < top radius");

  // Probe: channel 0 carries Rayleigh, 1 Mie, 2 ozone, each with unit coefficient, so that
  // extinctionAt(probe, r) = (d_R(r), d_M(r), d_O(r)).
  m.probe_ = m.geometry_;
  m.probe_.rayleigh_scattering = glm::dvec3(1.0, 0.0, 0.0);
  m.probe_.mie_scattering = glm::dvec3(0.0, 1.0, 0.0);
  m.probe_.mie_extinction = glm::dvec3(0.0, 1.0, 0.0);
  m.probe_.absorption_extinction = glm::dvec3(0.0, 0.0, 1.0);

  const size_t n = wavelengthsNm.size();
  for (auto* v : {&m.rayleighScattering_, &m.mieScattering_, &m.mieExtinction_, &m.ozoneAbsorption_,
                  &m.solarIrradiance_, &m.groundAlbedo_})
    v->resize(n);
  for (size_t i = 0; i < n; ++i) {
    const shared::AtmosphereParameters& t = triples[i / 3];
    const int c = int(i % 3);
    m.rayleighScattering_[i] = t.rayleigh_scattering[c];
    m.mieScattering_[i] = t.mie_scattering[c];
    m.mieExtinction_[i] = t.mie_extinction[c];
    m.ozoneAbsorption_[i] = t.absorption_extinction[c];
    m.solarIrradiance_[i] = t.solar_irradiance[c];
    m.groundAlbedo_[i] = t.ground_albedo[c];
    for (double v : {m.rayleighScattering_[i], m.mieScattering_[i], m.mieExtinction_[i], m.ozoneAbsorption_[i],
                     m.solarIrradiance_[i], m.groundAlbedo_[i]})
      if (!(v >= 0.0) || !std::isfinite(v))
        throw std::invalid_argument("SpectralMedium: negative or non-finite coefficient at " +
                                    std::to_string(wavelengthsNm[i]) + " nm");
    if (m.mieScattering_[i] > m.mieExtinction_[i])
      throw std::invalid_argument("SpectralMedium: Mie scattering exceeds Mie extinction");
    m.maxExtinctionPerDensity_ = glm::max(m.maxExtinctionPerDensity_, m.extinctionPerDensity(int(i)));
  }

  std::vector<double> altitudes;
  for (const shared::DensityProfile* profile :
       {&m.geometry_.rayleigh_density, &m.geometry_.mie_density, &m.geometry_.absorption_density}) {
    altitudes.push_back(profile->layer0.width);
    addClampAltitudes(profile->layer0, &altitudes);
    addClampAltitudes(profile->layer1, &altitudes);
  }
  for (double h : altitudes) {
    const double radius = m.geometry_.bottom_radius + h;
    if (std::isfinite(radius) && radius > m.geometry_.bottom_radius && radius < m.geometry_.top_radius)
      m.densityBreakRadii_.push_back(radius);
  }
  std::sort(m.densityBreakRadii_.begin(), m.densityBreakRadii_.end());
  m.densityBreakRadii_.erase(std::unique(m.densityBreakRadii_.begin(), m.densityBreakRadii_.end()),
                             m.densityBreakRadii_.end());
  // Three profiles give at most 3 x (1 + 2 + 2) = 15 candidates.
  if (m.densityBreakRadii_.size() > size_t(kMaxDensityBreaks)) m.densityBreakRadii_.resize(size_t(kMaxDensityBreaks));
  return m;
}

}  // namespace firmament::reference
