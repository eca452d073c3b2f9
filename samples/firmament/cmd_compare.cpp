// `firmament compare TEST.exr REFERENCE.exr`: error metrics of a render against a reference, an
// optional relative-error heat map and a JSON copy of the metrics (definitions: docs/formats.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/image_metrics.h"
#include "samples/firmament/command.h"

namespace firmament::cli {
namespace {

std::string formatValue(double v) {
  char buffer[32];
  if (std::isnan(v)) return "n/a";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::snprintf(buffer, sizeof(buffer), "%.4g", v);
  return buffer;
}

std::string formatPercent(double v) {
  if (!std::isfinite(v)) return formatValue(v);
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3f %%", 100.0 * v);
  return buffer;
}

void printRow(const char* name, const ErrorStats& s) {
  std::printf("  %-10s %12s %12s %12s %12s %12s %12s\n", name, formatValue(s.rmse).c_str(),
              formatPercent(s.relativeRmse).c_str(), formatValue(s.maxAbsError).c_str(),
              formatValue(s.meanBias).c_str(), formatPercent(s.relativeMeanBias).c_str(),
              formatValue(s.meanReference).c_str());
}

void printMetrics(const std::string& testPath, const std::string& referencePath, const ImageMetrics& m) {
  std::printf("test:      %s\nreference: %s\n", testPath.c_str(), referencePath.c_str());
  std::printf("size:      %d x %d, %zu pixels compared\n\n", m.width, m.height, m.comparedPixels);
  std::printf("  %-10s %12s %12s %12s %12s %12s %12s\n", "", "RMSE", "rel. RMSE", "max |err|", "bias", "rel. bias",
              "mean ref.");
  printRow("luminance", m.luminance);
  printRow("R", m.rgb[0]);
  printRow("G", m.rgb[1]);
  printRow("B", m.rgb[2]);
  std::printf("\nPSNR (luminance, peak %s cd/m^2): %s dB\n", formatValue(m.peakLuminance).c_str(),
              formatValue(m.psnrDb).c_str());
  std::printf("mean relative luminance error:   %s (floor %s cd/m^2)\n",
              formatPercent(m.meanRelativeLuminanceError).c_str(), formatValue(m.relativeErrorFloor).c_str());
  std::printf("non-finite pixels:               %zu test, %zu reference\n", m.nonFiniteTest, m.nonFiniteReference);
}

int runCompare(const Args& args) {
  const std::string testPath = args.positionals[0];
  const std::string referencePath = args.positionals[1];
  const double scale = args.number("scale", 0.1);
  if (!(scale > 0.0)) throw InputError("option --scale: must be > 0, got " + formatValue(scale));

  // Fail on an unwritable output before spending time on the comparison.
  for (const char* option : {"heatmap", "json"})
    if (auto out = args.get(option)) {
      const std::filesystem::path folder = std::filesystem::path(*out).parent_path();
      if (!folder.empty() && !std::filesystem::is_directory(folder))
        throw InputError("option --" + std::string(option) + ": folder '" + folder.string() + "' does not exist");
    }

  const Image test = readExr(testPath);
  const Image reference = readExr(referencePath);
  if (test.width != reference.width || test.height != reference.height)
    throw InputError("image sizes differ: '" + testPath + "' is " + std::to_string(test.width) + "x" +
                     std::to_string(test.height) + ", reference '" + referencePath + "' is " +
                     std::to_string(reference.width) + "x" + std::to_string(reference.height));
  const ImageMetrics metrics = compareImages(test, reference);
  printMetrics(testPath, referencePath, metrics);

  if (auto heatmap = args.get("heatmap")) {
    writeErrorHeatmapPng(*heatmap, test, reference, scale);
    std::printf("heat map:  %s (relative luminance error, 0 .. %s)\n", heatmap->c_str(), formatPercent(scale).c_str());
  }
  if (auto json = args.get("json")) {
    nlohmann::ordered_json document = nlohmann::ordered_json::parse(metricsToJson(metrics));
    document["test"] = testPath;
    document["reference"] = referencePath;
    if (args.has("heatmap")) document["heatmap_scale"] = scale;
    writeTextFileAtomically(*json, document.dump(2) + "\n");
    std::printf("metrics:   %s\n", json->c_str());
  }
  return kExitOk;
}

const CommandRegistration registration{Command{
    "compare",
    "error metrics of an image against a reference (B), an error heat map",
    "compare A.exr B.exr [--heatmap OUT.png] [--scale 0.1] [--json OUT.json]",
    {
        {"heatmap", "OUT.png", "write the per-pixel relative luminance error as a viridis heat map"},
        {"scale", "E", "relative error shown as the top colour of the heat map (default 0.1 = 10 %)"},
        {"json", "OUT.json", "write the metrics as JSON (docs/formats.md)"},
    },
    2,
    2,
    runCompare,
}};

}  // namespace
}  // namespace firmament::cli
