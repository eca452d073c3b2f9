// `firmament validate kider DATA_DIR --out DIR`: the CPU reference (and the fast GPU path, labelled
// apart) against the measured skies of Kider et al. 2014 with the published evaluation's conventions
// and error measure (docs/validation.md).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/log.h"
#include "eval/kider_validation.h"
#include "gpu/context.h"
#include "samples/firmament/command.h"

namespace firmament::cli {
namespace {

int runValidate(const Args& args) {
  const std::string what = args.positionals.at(0);
  if (what != "kider") throw InputError("firmament validate: unknown data set '" + what + "' (kider)");
  if (args.positionals.size() < 2) throw InputError("firmament validate kider: DATA_DIR is required");
  const std::filesystem::path dataDir = args.positionals.at(1);
  const auto outOption = args.get("out");
  if (!outOption) throw InputError("firmament validate: --out DIR is required");
  const std::filesystem::path out = *outOption;

  KiderValidationSettings settings;
  settings.quality.samplesPerPixel = args.integer("spp", settings.quality.samplesPerPixel, 1, 1 << 22);
  settings.quality.threads = args.integer("threads", 0, 0, 1024);
  settings.utcOffsetHours = args.number("utc-offset", settings.utcOffsetHours);
  settings.latitudeDeg = args.number("lat", settings.latitudeDeg);
  settings.longitudeDeg = args.number("lon", settings.longitudeDeg);
  if (const auto refit = args.get("refit")) {
    const auto method = kiderAzimuthRefitFromName(*refit);
    if (!method) throw InputError("--refit '" + *refit + "': expected published, log-rings or none");
    settings.azimuthRefit = *method;
  }
  if (const auto solar = args.get("solar-spectrum")) {
    const auto spectrum = kiderSolarSpectrumFromName(*solar);
    if (!spectrum) throw InputError("--solar-spectrum '" + *solar + "': expected instrument or band-means");
    settings.solarSpectrum = *spectrum;
  }
  settings.instrumentFwhmNm = args.number("instrument-fwhm", settings.instrumentFwhmNm);
  if (!(settings.instrumentFwhmNm > 0.0 && settings.instrumentFwhmNm <= settings.kMaxInstrumentFwhmNm))
    throw InputError("--instrument-fwhm " + *args.get("instrument-fwhm") +
                     ": expected a width in nm, > 0 and <= " + std::to_string(int(settings.kMaxInstrumentFwhmNm)));
  if (args.has("no-refit")) settings.azimuthRefit = KiderValidationSettings::AzimuthRefit::none;
  settings.gpu = !args.has("no-gpu");

  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError("--out " + out.string() + ": cannot create the folder: " + ec.message());
  std::unique_ptr<gpu::Context> context;
  if (settings.gpu) {
    gpu::ContextOptions options;
    options.device = args.getOr("device", "");
    context = std::make_unique<gpu::Context>(options);
  }
  KiderValidationResult result = runKiderValidation(dataDir, settings, context.get());
  writeKiderValidationOutputs(out, settings, result);
  char line[200];
  std::snprintf(line, sizeof(line), "total RMSE %.2f e-3 W m^-2 sr^-1 nm^-1 over %zu captures (Bruneton 2008: 11.2)",
                result.totalRmseSpectral, result.captures.size());
  logInfo(line);
  logInfo("wrote " + (out / "results.csv").string() + ", per_direction.csv, per_wavelength.csv, report.md");
  return kExitOk;
}

const CommandRegistration registration{Command{
    "validate",
    "render the measured directions of real captured skies and report the error (docs/validation.md)",
    "validate kider DATA_DIR --out DIR [--spp N] [--no-gpu] [--refit published|log-rings|none] [--solar-spectrum "
    "instrument|band-means] [--instrument-fwhm NM] [--utc-offset H] [--lat D --lon D]",
    {
        {"out", "DIR", "output folder (created): results.csv, per_direction.csv, per_wavelength.csv, report.md"},
        {"spp", "N", "reference Monte Carlo paths per direction (default 4096)"},
        {"threads", "N", "reference worker threads (default: all cores)"},
        {"no-gpu", "", "skip the fast GPU path's luminance comparison"},
        {"refit", "METHOD",
         "sun-azimuth re-fit: published (default; the published evaluation's method), log-rings, or none"},
        {"no-refit", "", "same as --refit none"},
        {"solar-spectrum", "WHICH",
         "solar spectrum under the compared spectra: instrument (default; G-173 through the instrument's line "
         "shape) or band-means (10-nm means, as the published comparison's models)"},
        {"instrument-fwhm", "NM", "the instrument line shape's full width at half maximum (default 3, ASD VNIR)"},
        {"utc-offset", "H", "capture names' local time = UTC + H hours (default -4, EDT)"},
        {"lat", "DEG", "site latitude (default 42.443449, Cornell)"},
        {"lon", "DEG", "site longitude (default -76.481962)"},
        deviceOption(),
    },
    2,
    2,
    runValidate,
}};

}  // namespace
}  // namespace firmament::cli
