// Outputs of `firmament validate kider`: results.csv, per_direction.csv, per_wavelength.csv and
// report.md (docs/validation.md).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"
#include "eval/kider_validation.h"

namespace firmament {
namespace {

std::string num(double v, const char* format = "%.6g") {
  if (std::isnan(v)) return "nan";
  char text[48];
  std::snprintf(text, sizeof(text), format, v);
  return text;
}

}  // namespace

void writeKiderValidationOutputs(const std::filesystem::path& outDir, const KiderValidationSettings& settings,
                                 const KiderValidationResult& result) {
  std::ostringstream csv;
  csv << "capture,utc,sun_zenith_deg,sun_azimuth_deg,rmse_spectral,rel_rmse_luminance,bias,azimuth_refit\n";
  for (const auto& c : result.captures)
    csv << c.capture << ',' << c.utc << ',' << num(c.sunZenithDeg, "%.4f") << ',' << num(c.sunAzimuthDeg, "%.4f") << ','
        << num(c.rmseSpectral, "%.4f") << ',' << num(c.relRmseLuminance) << ',' << num(c.bias, "%.4f") << ','
        << c.azimuthRefit << '\n';
  writeTextFileAtomically(outDir / "results.csv", csv.str());

  std::ostringstream dirs;
  dirs << "capture,index,file_azimuth_deg,azimuth_deg,zenith_deg,measured_luminance,reference_luminance,"
          "reference_luminance_se,gpu_luminance,rmse_spectral,bias_spectral\n";
  for (const auto& c : result.captures)
    for (const auto& d : c.directions)
      dirs << c.capture << ',' << d.index << ',' << num(d.fileAzimuthDeg) << ',' << num(d.azimuthDeg) << ','
           << num(d.zenithDeg) << ',' << num(d.measuredLuminance) << ',' << num(d.modelLuminance) << ','
           << num(d.modelLuminanceStandardError) << ',' << num(d.gpuLuminance) << ',' << num(d.rmseSpectral, "%.4f")
           << ',' << num(d.biasSpectral, "%.4f") << '\n';
  writeTextFileAtomically(outDir / "per_direction.csv", dirs.str());

  // Per wavelength, over the directions of each capture and over all captures.
  std::ostringstream wl;
  wl << "capture,wavelength_nm,measured_mean,reference_mean,rmse_spectral,bias_spectral\n";
  std::vector<double> allSe(result.wavelengths.size(), 0.0), allBias(result.wavelengths.size(), 0.0);
  std::vector<double> allMeasured(result.wavelengths.size(), 0.0), allModel(result.wavelengths.size(), 0.0);
  size_t allCount = 0;
  for (const auto& c : result.captures) {
    for (size_t i = 0; i < result.wavelengths.size(); ++i) {
      double se = 0.0, bias = 0.0, measured = 0.0, model = 0.0;
      for (const auto& d : c.directions) {
        const double e = d.model[i] - d.measured[i];
        se += e * e, bias += e, measured += d.measured[i], model += d.model[i];
      }
      const double n = double(std::max<size_t>(c.directions.size(), 1));
      wl << c.capture << ',' << num(result.wavelengths[i]) << ',' << num(measured / n) << ',' << num(model / n) << ','
         << num(1e3 * std::sqrt(se / n), "%.4f") << ',' << num(1e3 * bias / n, "%.4f") << '\n';
      allSe[i] += se, allBias[i] += bias, allMeasured[i] += measured, allModel[i] += model;
    }
    allCount += c.directions.size();
  }
  for (size_t i = 0; i < result.wavelengths.size() && allCount; ++i)
    wl << "all," << num(result.wavelengths[i]) << ',' << num(allMeasured[i] / allCount) << ','
       << num(allModel[i] / allCount) << ',' << num(1e3 * std::sqrt(allSe[i] / allCount), "%.4f") << ','
       << num(1e3 * allBias[i] / allCount, "%.4f") << '\n';
  writeTextFileAtomically(outDir / "per_wavelength.csv", wl.str());

  std::ostringstream md;
  md << "# Validation against measured skies (Kider et al. 2014)\n\n"
     << "Captures: " << result.captures.size()
     << ". Model: the CPU reference (spectral, double precision, all "
        "orders; docs/reference.md), "
     << settings.quality.samplesPerPixel << " paths per direction, " << settings.quality.wavelengthCount
     << " wavelengths 360 + 11.75 i nm. Run time " << num(result.seconds, "%.1f") << " s.\n\n"
     << "Error measure (Bruneton 2017, as published): per capture, the RMS over the directions and over "
     << result.wavelengths.size() << " wavelengths (" << num(result.wavelengths.front()) << "–"
     << num(result.wavelengths.back())
     << " nm) of the spectral radiance difference, in 10⁻³ W·m⁻²·sr⁻¹·nm⁻¹; "
        "total = sqrt(mean over captures of RMSE²). Nothing is fitted to the captures (docs/validation.md).\n\n"
     << "## Total\n\n| model | total RMSE (10⁻³ W·m⁻²·sr⁻¹·nm⁻¹) |\n|---|---|\n"
     << "| **Firmament CPU reference (this run)** | **" << num(result.totalRmseSpectral, "%.1f") << "** |\n";
  for (const auto& p : publishedKiderResults())
    md << "| " << p.model << " (published) | " << num(p.totalRmse, "%.1f") << " |\n";
  md << "\n## Per capture\n\nThe reference noise RMSE is sqrt(mean(SE²)) of its Monte Carlo standard errors over the "
        "same "
        "directions and wavelengths: it adds in quadrature to the true RMSE.\n\n"
     << "| capture | UTC | sun zenith ° | sun azimuth ° (computed → re-fitted) | RMSE spectral | bias | rel. RMSE "
        "luminance | reference noise RMSE | reference s |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : result.captures)
    md << "| " << c.capture << " | " << c.utc << " | " << num(c.sunZenithDeg, "%.2f") << " | "
       << num(c.sunAzimuthComputedDeg, "%.2f") << " → " << num(c.sunAzimuthDeg, "%.2f") << " | "
       << num(c.rmseSpectral, "%.2f") << " | " << num(c.bias, "%+.2f") << " | " << num(100 * c.relRmseLuminance, "%.2f")
       << " % | " << num(c.referenceNoiseRmse, "%.2f") << " | " << num(c.referenceSeconds, "%.1f") << " |\n";
  if (!result.gpuDevice.empty()) {
    md << "\n## The fast GPU path in the same directions (luminance only)\n\n"
       << "Rendered as a " << settings.gpuWidth << "×" << settings.gpuHeight
       << " equirectangular image with the same atmosphere (three wavelengths; the grass albedo as its "
          "luminance-weighted mean, "
       << num(grassAlbedoLuminanceWeighted(), "%.4f")
       << "), read bilinearly at each direction. Device: " << result.gpuDevice
       << ".\n\n| capture | rel. RMSE luminance vs measured | vs the CPU reference |\n|---|---|---|\n";
    for (const auto& c : result.captures)
      md << "| " << c.capture << " | " << num(100 * c.gpuRelRmseLuminance, "%.2f") << " % | "
         << num(100 * c.gpuVsReferenceRelRmse, "%.2f") << " % |\n";
    md << "| total (RMS over captures) | " << num(100 * result.totalGpuRelRmseLuminance, "%.2f") << " % | |\n";
  }
  md << "\n## Settings (the published comparison's, README)\n\n"
     << "- Site " << settings.latitudeDeg << "°, " << settings.longitudeDeg << "°, " << settings.siteHeightM
     << " m (for the sun position); capture names are local time, UTC = local − (" << settings.utcOffsetHours
     << " h).\n"
     << "- Sun: astro ephemeris (ERFA), apparent zenith as computed; azimuth "
     << (settings.azimuthRefit == KiderValidationSettings::AzimuthRefit::none
             ? std::string("as computed")
             : std::string(settings.azimuthRefit == KiderValidationSettings::AzimuthRefit::published
                               ? "re-fitted as the published code does (mirror asymmetry of the interpolated, "
                                 "spectrally integrated radiance)"
                               : "re-fitted by the mirror asymmetry of log radiances on the measured rings") +
                   " within ±" + num(settings.refitHalfRangeDeg) + "° in " + num(settings.refitStepDeg) +
                   "° steps; the method per capture is in results.csv")
     << ".\n"
     << "- File azimuths are counter-clockwise from north: azimuth = (360 − a) mod 360. Sample 0 "
     << (settings.replaceSampleZero ? "replaced by the mean of samples 1 and 31" : "kept") << ".\n"
     << "- Atmosphere: Bruneton's Earth with Ångström α = 0.8, β = 0.04, Cornette–Shanks g = 0.7, aerosol "
        "single-scattering albedo 0.8, aerosol scale height 1.2 km, no ozone, ground at sea level (6360 km), grass "
        "spectral albedo (Feister & Grewe 1995), camera "
     << settings.cameraHeightM
     << " m above the ground; solar spectrum ASTM G-173 at 1 au, scaled to the "
        "capture date's Earth-Sun distance.\n"
     << "- Solar spectrum under the compared spectra: "
     << (settings.solarSpectrum == KiderValidationSettings::SolarSpectrum::instrument
             ? "ASTM G-173 read through the instrument's line shape, a Gaussian of " + num(settings.instrumentFwhmNm) +
                   " nm FWHM (`--solar-spectrum instrument`, the default)"
             : std::string("the atmosphere's 10-nm means of ASTM G-173, as the published comparison's models used "
                           "(`--solar-spectrum band-means`)"))
     << "; luminances use the 10-nm means.\n"
     << "- Files: results.csv (per capture), per_direction.csv, per_wavelength.csv.\n";
  writeTextFileAtomically(outDir / "report.md", md.str());
}

}  // namespace firmament
