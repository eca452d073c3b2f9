// Outputs of `firmament bench atmosphere`: results.csv, report.md and the error-against-run-time
// plots (docs/bench.md).
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/svg_xy_plot.h"
#include "eval/atmosphere_bench.h"

namespace firmament {
namespace {

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[48];
  std::snprintf(text, sizeof(text), "%.*f", digits, v);
  return text;
}

std::string general(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[48];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

// RFC 4180: quote a field that holds a comma, a quote or a line break.
std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The error that remains once the reference's own noise is taken out: E[(a − b̂)²] = (a − b)² + SE²
// for an unbiased reference b̂, so mean((a − b)²) ≈ measured − mean(SE²) (floored at 0).
double noiseCorrectedMse(const BenchRow& row, const BenchReference& ref) {
  const double measured = row.relRmse * row.relRmse * ref.meanSquaredLuminance;
  return std::max(measured - ref.meanSquaredNoise, 0.0);
}

}  // namespace

void writeAtmosphereBenchOutputs(const AtmosphereBenchConfig& config, const AtmosphereBenchResult& result) {
  // --- results.csv ---
  std::ostringstream csv;
  csv << "knob,value,scenario,precompute_ms,frame_ms,rel_rmse,psnr_db,max_rel_err,device\n";
  for (const auto& r : result.rows)
    csv << csvField(r.knob) << ',' << csvField(r.value) << ',' << csvField(r.scenario) << ','
        << fixed(r.precomputeMs, 4) << ',' << fixed(r.frameMs, 4) << ',' << general(r.relRmse) << ','
        << fixed(r.psnrDb, 3) << ',' << general(r.maxRelErr) << ',' << csvField(r.device) << '\n';
  writeTextFileAtomically(config.outDir / "results.csv", csv.str());

  std::map<std::string, const BenchReference*> references;
  for (const auto& ref : result.references) references[ref.scenario] = &ref;

  // --- plots: per scenario, error against the cost each knob changes ---
  std::vector<std::string> plots;
  for (const auto& scenario : config.scenarios) {
    for (bool tables : {true, false}) {
      XyPlot plot;
      plot.title = "bench atmosphere: " + scenario.name + (tables ? " (table knobs)" : " (frame knobs)");
      plot.xLabel = tables ? "precompute_ms (tables, median)" : "frame_ms (per-frame passes, median)";
      plot.yLabel = "rel_rmse of luminance vs reference";
      plot.logX = plot.logY = true;
      size_t colour = 0;
      for (const auto& knob : config.knobs) {
        if (knob.tables != tables) continue;
        XyPlotSeries s;
        s.name = knob.name;
        s.colour = plotColour(colour++);
        for (const auto& r : result.rows)
          if (r.knob == knob.name && r.scenario == scenario.name) {
            s.x.push_back(tables ? r.precomputeMs : r.frameMs);
            s.y.push_back(r.relRmse);
            s.labels.push_back(r.value);
          }
        plot.series.push_back(std::move(s));
      }
      if (plot.series.empty()) continue;
      if (auto it = references.find(scenario.name); it != references.end())
        plot.lines.push_back({"reference noise (expected rel_rmse)", it->second->noiseRelRmse, "#888888"});
      const std::string name = "plot_" + scenario.name + (tables ? "_tables" : "_frame") + ".svg";
      writeTextFileAtomically(config.outDir / name, renderXySvg(plot));
      plots.push_back(name);
    }
  }

  // --- report.md ---
  std::ostringstream md;
  md << "# Atmosphere benchmark\n\n"
     << "Device: **" << result.device << "**";
  if (!config.environmentNote.empty()) md << "  \n" << config.environmentNote;
  md << "  \nRun: " << (config.quick ? "`--quick`" : "full") << ", " << result.rows.size() << " measurements, "
     << fixed(result.seconds, 1) << " s. Timings are medians of " << config.repeats
     << " repeats after a warm-up; precompute_ms recomputes the tables each time (no memory or disk cache).";
  if (!result.timingNote.empty()) md << " Note: " << result.timingNote << ".";
  md << "\n\n"
     << "Errors are of the luminance Y against the CPU reference (spectral, all orders; docs/reference.md):\n"
     << "rel_rmse = sqrt(mean((Ya − Yb)²)) / sqrt(mean(Yb²)); psnr_db = 10 log10(max(Yb)² / mean((Ya − Yb)²));\n"
     << "max_rel_err = max over pixels of |Ya − Yb| / max(Yb, ε), ε = 1 % of mean(Yb). Definitions: docs/bench.md.\n\n";

  md << "## Scenarios and the reference's own noise\n\n"
     << "| scenario | view | size | reference spp | wavelengths | render s | median SE/Y | p95 SE/Y | noise-only "
        "rel_rmse | "
        "noise-only PSNR dB |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& scenario : config.scenarios) {
    auto it = references.find(scenario.name);
    if (it == references.end()) continue;
    const BenchReference& r = *it->second;
    md << "| " << scenario.name << " | " << scenario.description << " | " << r.width << "×" << r.height << " | "
       << r.samplesPerPixel << " | " << r.wavelengths << " | " << fixed(r.seconds, 1)
       << (r.fromCache ? " (cached)" : "") << " | " << fixed(100 * r.medianRelativeNoise, 2) << " % | "
       << fixed(100 * r.p95RelativeNoise, 2) << " % | " << general(r.noiseRelRmse) << " | " << fixed(r.noisePsnrDb, 1)
       << " |\n";
  }
  md << "\nThe noise-only columns are what the reference's Monte Carlo noise alone costs in expectation "
        "(sqrt(mean(SE²)/mean(Y²)) and 10 log10(max(Y)²/mean(SE²))): a measured error near them is the "
        "reference's, not the fast path's. The corrected columns below subtract mean(SE²) from the mean "
        "squared error.\n\n";

  md << "## Shipped defaults against the targets\n\n"
     << "| scenario | precompute_ms | frame_ms | rel_rmse | psnr_db | max_rel_err | noise-corrected rel_rmse | "
        "noise-corrected PSNR dB | target |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : result.rows) {
    if (r.knob != "default") continue;
    auto it = references.find(r.scenario);
    double correctedRel = NAN, correctedPsnr = NAN;
    if (it != references.end()) {
      const double mse = noiseCorrectedMse(r, *it->second);
      correctedRel = std::sqrt(mse / it->second->meanSquaredLuminance);
      correctedPsnr = 10.0 * std::log10(it->second->peakLuminance * it->second->peakLuminance / mse);
    }
    std::string target = "—";
    if (r.scenario == "noon")
      target = std::string("≥ 45 dB: ") + (r.psnrDb >= 45        ? "met"
                                           : correctedPsnr >= 45 ? "met after noise correction"
                                                                 : "**not met**");
    if (r.scenario == "sunset")
      target = std::string("≥ 40 dB: ") + (r.psnrDb >= 40        ? "met"
                                           : correctedPsnr >= 40 ? "met after noise correction"
                                                                 : "**not met**");
    md << "| " << r.scenario << " | " << fixed(r.precomputeMs, 2) << " | " << fixed(r.frameMs, 2) << " | "
       << general(r.relRmse) << " | " << fixed(r.psnrDb, 2) << " | " << general(r.maxRelErr) << " | "
       << general(correctedRel) << " | " << fixed(correctedPsnr, 1) << " | " << target << " |\n";
  }
  {
    double tablesMs = 0.0;
    for (const auto& r : result.rows)
      if (r.knob == "default" && r.scenario == (config.scenarios.empty() ? "" : config.scenarios.front().name))
        tablesMs = r.precomputeMs;
    md << "\nTables of the defaults (every table pass of the f_ms form), median: **" << fixed(tablesMs, 2)
       << " ms** (target ≤ 100 ms: " << (tablesMs <= 100 ? "met" : "**not met**") << ")";
    if (!result.defaultTablePasses.empty()) {
      md << "; per pass:";
      for (const auto& p : result.defaultTablePasses) md << " " << p.label << " " << fixed(p.milliseconds, 2) << " ms;";
    }
    md << "\n\n";
  }
  if (!result.fullFrame.empty()) {
    md << "Full-resolution frame (scenario " << config.scenarios.front().name
       << ", defaults, tables cached), median:\n\n"
       << "| method | size | frame_ms | passes | target |\n|---|---|---|---|---|\n";
    for (const auto& f : result.fullFrame) {
      std::string passes;
      for (const auto& p : f.passes)
        if (p.label.rfind("atmosphere/", 0) != 0) passes += p.label + " " + fixed(p.milliseconds, 2) + " ms; ";
      md << "| " << f.method << " | " << f.width << "×" << f.height << " | " << fixed(f.frameMs, 2) << " | " << passes
         << " | " << (f.method == "lut" ? std::string("≤ 50 ms: ") + (f.frameMs <= 50 ? "met" : "**not met**") : "—")
         << " |\n";
    }
    md << "\n";
  }

  md << "## Knobs, one at a time around the defaults\n\n"
     << "Each table varies one field of `SkyRenderOptions`; every other field keeps its default (the default value is "
        "marked *). Plots: error against the cost the knob changes, one per scenario and cost (";
  for (size_t i = 0; i < plots.size(); ++i) md << (i ? ", " : "") << "[" << plots[i] << "](" << plots[i] << ")";
  md << ").\n\n";
  for (const auto& knob : config.knobs) {
    md << "### " << knob.name << "\n\n"
       << knob.description << " (default " << knob.defaultValue << "; cost: " << (knob.tables ? "precompute" : "frame")
       << ").\n\n"
       << "| value | scenario | precompute_ms | frame_ms | rel_rmse | psnr_db | max_rel_err "
          "|\n|---|---|---|---|---|---|---|\n";
    for (const auto& r : result.rows)
      if (r.knob == knob.name)
        md << "| " << r.value << (r.value == knob.defaultValue ? "*" : "") << " | " << r.scenario << " | "
           << fixed(r.precomputeMs, 2) << " | " << fixed(r.frameMs, 2) << " | " << general(r.relRmse) << " | "
           << fixed(r.psnrDb, 2) << " | " << general(r.maxRelErr) << " |\n";
    md << "\n";
  }
  writeTextFileAtomically(config.outDir / "report.md", md.str());
}

}  // namespace firmament
