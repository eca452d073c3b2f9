#include "eval/cloud_calibration.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "clouds/reference_clouds.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "core/scene.h"
#include "eval/cloud_pixels_csv.h"
#include "eval/cloud_reference_cache.h"
#include "eval/scenarios.h"
#include "sky/scene_cloud_medium.h"
#include "sky/sky_renderer.h"

namespace firmament {
namespace {

struct CalibrationScene {
  std::string name, group, description, text;
};

// The calibration scenes are scene files (eval/scenarios/calibration/*.json, listed by group in its
// index.json), separate from the bench's scenarios (eval/scenarios/clouds/; cumulus_noon: seed 1,
// 1500-3000 m, coverage 0.6, sun 30 deg; stratocumulus_sunset: seed 1, 1000-2000 m, coverage 0.7, sun
// 85 deg looking towards it): other seeds, layer heights, coverages, sun angles and view directions; two
// thinner layers (extinction x 0.15) keep the fit from buying thick clouds' light with thin clouds'
// energy. Views from above, a far view over the horizon and low suns (76-85 deg) are among them because
// constants fitted without such views held out worse on the bench's above_clouds, horizon and
// cumulus_low_sun. Each is rendered at its file's size, or at the index's quick_size with --quick.
std::vector<CalibrationScene> calibrationScenes(bool quick) {
  const nlohmann::json index = evalScenarioIndex("calibration");
  const nlohmann::json& quickSize = index.at("quick_size");
  std::vector<CalibrationScene> list;
  for (const nlohmann::json& s : index.at("scenarios")) {
    const std::string name = s.at("name").get<std::string>();
    nlohmann::json scene = nlohmann::json::parse(evalScenarioText("calibration/" + name + ".json"));
    if (quick) {
      scene["camera"]["width"] = quickSize.at("width");
      scene["camera"]["height"] = quickSize.at("height");
    }
    list.push_back({name, s.at("group").get<std::string>(), s.at("description").get<std::string>(), scene.dump()});
  }
  return list;
}

struct Prepared {
  CalibrationScene scene;
  CloudReferenceImage reference;
  std::unique_ptr<SkyRenderer> renderer;  // one per scene: each keeps its seed's noise baked (~2 s a bake)
};

std::string number(double x) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.4f", x);
  return s;
}

}  // namespace

namespace {
const std::vector<std::string> kGroups = {"cumulus", "stratocumulus", "stratus", "cumulonimbus", "cirrus", "all"};
}  // namespace

void checkCloudCalibrationConfig(const CloudCalibrationConfig& config) {
  if (!config.group.empty() && std::find(kGroups.begin(), kGroups.end(), config.group) == kGroups.end()) {
    std::string names;
    for (const std::string& g : kGroups) names += (names.empty() ? "" : ", ") + g;
    throw InputError("--group " + config.group + ": no such calibration group (" + names + ")");
  }
  cloudPhaseModelFromName(config.phase, "firmament bench clouds --calibrate --phase");
}

CloudCalibrationResult runCloudCalibration(gpu::Context& context, const CloudCalibrationConfig& config) {
  checkCloudCalibrationConfig(config);
  const CloudPhaseModel phase = cloudPhaseModelFromName(config.phase, "--phase");
  CloudCalibrationResult result;
  result.device = context.description();
  SkyRenderOptions options;
  options.clouds.ambient = false;
  options.clouds.aerialPerspective = AerialPerspective::Off;
  if (config.lightSteps > 0) options.clouds.lightSteps = config.lightSteps;
  const int spp = config.samplesPerPixel > 0 ? config.samplesPerPixel : (config.quick ? 64 : 128);

  // 1. The references (all orders), once.
  auto t0 = std::chrono::steady_clock::now();
  std::vector<Prepared> prepared;
  auto inGroup = [](const std::string& sceneGroup, const std::string& group) {
    return group == "all" ? sceneGroup == "cumulus" || sceneGroup == "stratocumulus" : sceneGroup == group;
  };
  for (const CalibrationScene& sc : calibrationScenes(config.quick)) {
    if (!config.group.empty() && !inGroup(sc.group, config.group)) continue;
    const Scene scene =
        Scene::parse(sc.text, "<calibration " + sc.name + ">", {"/clouds/lighting/phase=" + config.phase});
    auto renderer = std::make_unique<SkyRenderer>(context);
    const RenderResult first = renderer->render(scene, options);
    const CloudSettings settings = CloudSettings::fromScene(scene);
    const CloudMedium medium = sceneCloudMedium(scene, first.view, context, options.cloudNoise);
    CloudReferenceSettings rs;
    rs.samplesPerPixel = spp;
    rs.threads = config.threads;
    const CloudPathTracer tracer(medium, settings.lighting, first.view.atmosphere, first.view.sunDirection,
                                 CloudEnvironment{}, rs);
    // Kept in DIR/references (eval/cloud_reference_cache.h), so a refit after a model change, or at more
    // paths per pixel once, pays for the references only the first time.
    bool cached = false;
    Prepared p{sc,
               cachedCloudReference(scene, tracer, glm::dvec3(0.0, 0.0, first.view.cameraRadius), first.view.camera,
                                    config.threads, options.cloudNoise, config.outDir / "references", sc.name, &cached),
               std::move(renderer)};
    logInfo("calibrate clouds: " + sc.name + " reference " + std::to_string(spp) + " paths/pixel " +
            (cached ? "from " + (config.outDir / "references").string() + " (rendered in " : "in ") +
            std::to_string(p.reference.seconds) + (cached ? " s)" : " s"));
    prepared.push_back(std::move(p));
  }
  result.referenceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();

  // The errors of one parameter set on the scenes of a group. With `pixelsColumn` (--images, the final
  // set) each scene's pixels are also written beside the reference's, from the same render
  // (DIR/images/SCENE_pixels.csv, the column so named).
  auto evaluate = [&](const std::string& group, double a, double b, double c, double d, double r, double ra, double mu0,
                      std::vector<CloudCalibrationSceneError>& out, const std::string& pixelsColumn = "") {
    out.clear();
    double sum = 0.0;
    for (const Prepared& p : prepared) {
      if (!inGroup(p.scene.group, group)) continue;
      const Scene scene = Scene::parse(
          p.scene.text, "<calibration " + p.scene.name + ">",
          {"/clouds/lighting/phase=" + config.phase, "/clouds/lighting/ms_octaves=" + std::to_string(config.octaves),
           "/clouds/lighting/ms_b=" + number(b), "/clouds/lighting/ms_a=" + number(std::min(a, b)),
           "/clouds/lighting/ms_c=" + number(c), "/clouds/lighting/ms_d=" + number(d),
           "/clouds/lighting/ms_r=" + number(r), "/clouds/lighting/ms_ra=" + number(ra),
           "/clouds/lighting/ms_low_sun_mu=" + number(mu0)});
      const RenderResult rendered = p.renderer->render(scene, options);
      if (!pixelsColumn.empty()) {
        std::filesystem::create_directories(config.outDir / "images");
        writeCloudPixelsCsv(config.outDir / "images" / (p.scene.name + "_pixels.csv"), rendered.view, p.reference,
                            {{pixelsColumn, cloudPixelLuminance(rendered.clouds)}});
      }
      const CloudReferenceError e = compareWithCloudReference(rendered.clouds, p.reference);
      out.push_back({p.scene.name, e.relRmse, e.noiseCorrected, e.noiseFloor, e.meanBias});
      sum += e.relRmse * e.relRmse;
    }
    return out.empty() ? 0.0 : sum / double(out.size());
  };

  // The pixels CSV's column for a final parameter set (empty without --images: none written).
  auto pixelsColumn = [&](const char* what, double a, double b, double c, double d, double r, double ra, double mu0) {
    if (!config.images) return std::string();
    char column[200];
    std::snprintf(column, sizeof(column), "%s a %.3f b %.3f c %.3f d %.3f r %.3f a_r %.3f mu_0 %.3f", what, a, b, c, d,
                  r, ra, mu0);
    return std::string(column);
  };

  // 2. Nelder-Mead over x = (b, a/b, c, d / 2), each clamped to [0, 1] (a <= b by construction; the
  // diffusion floor's weight d in [0, 2], 1 being the Eddington slab's own value).
  for (const std::string& group : kGroups) {
    if (!config.group.empty() && group != config.group) continue;
    CloudCalibrationFit fit;
    fit.group = group;
    // The simplex's dimension: (b, a/b, c, d/2[, r/4, a_r]), or (r/4, a_r) alone with the octaves'
    // constants fixed at the shipped fit (reflectionOnly).
    const bool rOnly = config.reflectionOnly;
    const int N = rOnly ? 2 : config.reflection ? 6 : 4;
    using Point = std::array<double, 6>;
    auto clamp01 = [](Point x) {
      for (double& v : x) v = std::clamp(v, 0.0, 1.0);
      return x;
    };
    std::vector<CloudCalibrationSceneError> scratch;
    // The group's shipped constants: its type's, or for "all" the joint fit. --reflection-only fits r and
    // a_r over the shipped reflected-light fit's octaves (not the octaves-alone
    // fit's, which for cumulus are not the shipped ones).
    const CloudMultipleScattering shipped =
        group == "all" ? cloudJointMultipleScattering(phase)
                       : cloudTypeMultipleScattering(cloudKindFromName(group), phase, config.reflection);
    auto f = [&](const Point& x) {
      ++fit.evaluations;
      // The low-sun scale stays at the group's shipped mu_0 while the other constants are fitted.
      if (rOnly)
        return evaluate(group, shipped.a, shipped.b, shipped.c, shipped.d, 4.0 * x[0], x[1], shipped.lowSunMu, scratch);
      return evaluate(group, x[0] * x[1], x[0], x[2], 2.0 * x[3], 4.0 * x[4], x[5], shipped.lowSunMu, scratch);
    };
    fit.lowSunMu = shipped.lowSunMu;
    if (config.evaluateDefaults) {
      // Rendered as overrides, so the numbers are those constants' on every scene of the group.
      fit.a = shipped.a, fit.b = shipped.b, fit.c = shipped.c, fit.d = shipped.d, fit.r = shipped.r,
      fit.ra = shipped.ra;
      fit.objectiveStart = evaluate(group, 0.5, 0.5, 0.5, 1.0, 0.0, 0.0, 0.0, fit.start);
      fit.objectiveFit = evaluate(group, fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu, fit.fit,
                                  pixelsColumn("shipped", fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu));
      char line[220];
      std::snprintf(
          line, sizeof(line),
          "calibrate clouds: %-14s shipped a %.3f b %.3f c %.3f d %.3f r %.3f a_r %.3f mu_0 %.3f: rms rel RMSE %.4f",
          group.c_str(), fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu, std::sqrt(fit.objectiveFit));
      logInfo(line);
      result.fits.push_back(std::move(fit));
      continue;
    }
    if (config.lowSunOnly) {
      // mu_0 alone: a sweep (the objective against mu_0 is worth seeing whole, and cheap: one parameter),
      // then golden sections inside the best point's neighbours.
      fit.a = shipped.a, fit.b = shipped.b, fit.c = shipped.c, fit.d = shipped.d, fit.r = shipped.r,
      fit.ra = shipped.ra;
      auto atMu = [&](double mu0, std::vector<CloudCalibrationSceneError>& out) {
        return evaluate(group, fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, mu0, out);
      };
      fit.objectiveStart = atMu(0.0, fit.start);
      std::vector<CloudCalibrationSweepPoint> sweep;
      for (int k = 0; k <= 16; ++k) {
        CloudCalibrationSweepPoint point{group, 0.05 * k, 0.0, {}};
        point.objective = atMu(point.lowSunMu, point.scenes);
        ++fit.evaluations;
        logInfo("calibrate clouds: " + group + " mu_0 " + number(point.lowSunMu) + ": rms rel RMSE " +
                number(std::sqrt(point.objective)));
        sweep.push_back(std::move(point));
      }
      const size_t best =
          size_t(std::min_element(sweep.begin(), sweep.end(),
                                  [](const auto& x, const auto& y) { return x.objective < y.objective; }) -
                 sweep.begin());
      double lo = sweep[best > 0 ? best - 1 : 0].lowSunMu, hi = sweep[std::min(best + 1, sweep.size() - 1)].lowSunMu;
      const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
      double f1 = atMu(x1, scratch), f2 = atMu(x2, scratch);
      fit.evaluations += 2;
      for (int k = 0; k < 6; ++k, ++fit.evaluations) {
        if (f1 < f2) {
          hi = x2, x2 = x1, f2 = f1, x1 = hi - phi * (hi - lo);
          f1 = atMu(x1, scratch);
        } else {
          lo = x1, x1 = x2, f1 = f2, x2 = lo + phi * (hi - lo);
          f2 = atMu(x2, scratch);
        }
      }
      fit.lowSunMu = sweep[best].objective <= std::min(f1, f2) ? sweep[best].lowSunMu : f1 < f2 ? x1 : x2;
      fit.objectiveFit = evaluate(group, fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu, fit.fit,
                                  pixelsColumn("fit", fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu));
      logInfo("calibrate clouds: " + group + " low-sun mu_0 " + number(fit.lowSunMu) + ": rms rel RMSE " +
              number(std::sqrt(fit.objectiveStart)) + " (off) -> " + number(std::sqrt(fit.objectiveFit)));
      result.lowSunSweep.insert(result.lowSunSweep.end(), sweep.begin(), sweep.end());
      result.fits.push_back(std::move(fit));
      continue;
    }
    // The simplex starts at the shipped constants (since): the objective is flat across quite
    // different (a, b, c, d), and from a fixed start the 90 evaluations could end on a point worse than
    // the shipped one (docs/clouds.md, "Calibration"); from there a fit can only improve on it.
    const bool fromZero = shipped.r <= 0.0;
    const Point start =
        rOnly ? Point{0.25, 0.5, 0, 0, 0, 0}
              : clamp01({shipped.b, shipped.b > 0.0 ? shipped.a / shipped.b : 1.0, shipped.c, 0.5 * shipped.d,
                         config.reflection ? (fromZero ? 0.25 : 0.25 * shipped.r) : 0.25 * shipped.r,
                         config.reflection && fromZero ? 0.5 : shipped.ra});
    std::array<Point, 7> simplex;
    simplex[0] = start;
    for (int i = 0; i < N; ++i) {
      simplex[i + 1] = start;
      simplex[i + 1][i] += start[i] + 0.25 <= 1.0 ? 0.25 : -0.25;
    }
    std::array<double, 7> value{};
    for (int i = 0; i <= N; ++i) value[i] = f(simplex[i]);
    fit.objectiveStart = evaluate(group, 0.5, 0.5, 0.5, 1.0, 0.0, 0.0, 0.0, fit.start);
    while (fit.evaluations < config.maxEvaluations) {
      std::vector<int> order(size_t(N) + 1);
      for (int i = 0; i <= N; ++i) order[size_t(i)] = i;
      std::sort(order.begin(), order.end(), [&](int i, int j) { return value[size_t(i)] < value[size_t(j)]; });
      const auto best = simplex[order[0]];
      const int worst = order[N];
      if (value[order[N]] - value[order[0]] < 1e-6 * std::max(value[order[0]], 1e-12)) break;
      Point centroid = start;  // the coordinates past N stay at the start's
      for (int d = 0; d < N; ++d) centroid[d] = 0.0;
      for (int k = 0; k < N; ++k)
        for (int d = 0; d < N; ++d) centroid[d] += simplex[order[k]][d] / double(N);
      auto along = [&](double t) {
        Point x = start;
        for (int d = 0; d < N; ++d) x[d] = centroid[d] + t * (simplex[worst][d] - centroid[d]);
        return clamp01(x);
      };
      const auto reflected = along(-1.0);
      const double fr = f(reflected);
      if (fr < value[order[0]]) {
        const auto expanded = along(-2.0);
        const double fe = f(expanded);
        if (fe < fr)
          simplex[worst] = expanded, value[worst] = fe;
        else
          simplex[worst] = reflected, value[worst] = fr;
      } else if (fr < value[order[N - 1]]) {
        simplex[worst] = reflected, value[worst] = fr;
      } else {
        const auto contracted = along(fr < value[worst] ? -0.5 : 0.5);
        const double fc = f(contracted);
        if (fc < std::min(fr, value[worst])) {
          simplex[worst] = contracted, value[worst] = fc;
        } else {  // shrink towards the best
          for (int k = 1; k <= N; ++k) {
            const int i = order[k];
            for (int d = 0; d < N; ++d) simplex[i][d] = best[d] + 0.5 * (simplex[i][d] - best[d]);
            value[i] = f(simplex[i]);
          }
        }
      }
    }
    int bestIndex = int(std::min_element(value.begin(), value.begin() + N + 1) - value.begin());
    const auto x = simplex[bestIndex];
    fit.b = x[0];
    fit.a = x[0] * x[1];
    fit.c = x[2];
    fit.d = 2.0 * x[3];
    fit.r = 4.0 * x[4];
    fit.ra = x[5];
    if (rOnly)
      fit.a = shipped.a, fit.b = shipped.b, fit.c = shipped.c, fit.d = shipped.d, fit.r = 4.0 * x[0], fit.ra = x[1];
    fit.objectiveFit = evaluate(group, fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu, fit.fit,
                                pixelsColumn("fit", fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, fit.lowSunMu));
    char line[256];
    std::snprintf(line, sizeof(line),
                  "calibrate clouds: %-14s a %.3f b %.3f c %.3f d %.3f r %.3f a_r %.3f: rms rel RMSE %.4f -> %.4f (%d "
                  "evaluations)",
                  group.c_str(), fit.a, fit.b, fit.c, fit.d, fit.r, fit.ra, std::sqrt(fit.objectiveStart),
                  std::sqrt(fit.objectiveFit), fit.evaluations);
    logInfo(line);
    result.fits.push_back(std::move(fit));
  }
  result.fitSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

void writeCloudCalibrationOutputs(const CloudCalibrationConfig& config, const CloudCalibrationResult& result) {
  std::string csv =
      "group,a,b,c,d,r,a_r,low_sun_mu,scene,rel_rmse,rel_rmse_noise_corrected,ref_noise_rel_rmse,mean_bias,at\n";
  std::string md =
      "# Cloud march: octave parameters fitted to the path tracer\n\n"
      "Calibration scenes (separate from `bench clouds`' scenarios), sunlight only, extinction x 0.3 (cu_thin, "
      "sc_thin x 0.15, the cumulonimbus x 0.1, cirrus at its own extinction), " +
      std::to_string(config.octaves) + " octaves, " +
      (config.lightSteps > 0 ? std::to_string(config.lightSteps) : std::string("the default's")) +
      " light steps, phase " + config.phase + " on both sides; reference: the CPU cloud path tracer (all orders, " +
      std::to_string(config.samplesPerPixel > 0 ? config.samplesPerPixel : (config.quick ? 64 : 128)) +
      " paths/pixel). Fit: Nelder-Mead over (b, a/b, c, d/2) from the group's shipped constants, minimising the "
      "mean squared rel RMSE of the clouds' luminance over the group's scenes. `start`: a = b = c = 0.5, d = 1 with "
      "the same multiple-scattering "
      "model (d: the Eddington diffusion floor's weight) and no reflected light (r = 0). r, a_r: the reflected light's "
      "weight and depth "
      "scale (cloudReflectedSource; 0 and unused when it is off). `corrected`: the reference's noise subtracted.\n\n";
  if (config.evaluateDefaults)
    md +=
        "**No fit (`--evaluate-defaults`)**: the columns `a b c d` and `at the fit` are each group's shipped constants "
        "(cloudTypeMultipleScattering; `all`: the joint fit) and their errors.\n\n";
  if (config.lowSunOnly)
    md +=
        "**The low-sun scale's mu_0 alone (`--low-sun`)**: every other constant at the group's shipped fit (with the "
        "reflected "
        "light); `start` is those constants with the scale off (mu_0 = 0), `at the fit` with the fitted mu_0. The "
        "sweep's points "
        "are in clouds_calibration_low_sun.csv.\n\n";
  if (!config.environmentNote.empty()) md += config.environmentNote + "\n\n";
  char line[512];
  std::snprintf(line, sizeof(line), "References %.1f s, fit %.1f s. Device: %s\n\n", result.referenceSeconds,
                result.fitSeconds, result.device.c_str());
  md += line;
  md += std::string("| group | a | b | c | d | r | a_r | mu_0 | evaluations | rms rel RMSE at ") +
        (config.lowSunOnly ? "mu_0 = 0" : "a = b = c = 0.5, d = 1") +
        " | at the fit |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& f : result.fits) {
    std::snprintf(line, sizeof(line), "| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %d | %.4f | %.4f |\n",
                  f.group.c_str(), f.a, f.b, f.c, f.d, f.r, f.ra, f.lowSunMu, f.evaluations,
                  std::sqrt(f.objectiveStart), std::sqrt(f.objectiveFit));
    md += line;
  }
  md +=
      "\n| group | scene | rel RMSE start | corrected | bias | rel RMSE fit | corrected | noise | bias |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& f : result.fits)
    for (size_t i = 0; i < f.fit.size() && i < f.start.size(); ++i) {
      const auto& s = f.start[i];
      const auto& e = f.fit[i];
      std::snprintf(line, sizeof(line), "| %s | %s | %.4f | %.4f | %+.3f | %.4f | %.4f | %.4f | %+.3f |\n",
                    f.group.c_str(), e.scene.c_str(), s.relRmse, s.noiseCorrected, s.meanBias, e.relRmse,
                    e.noiseCorrected, e.noiseFloor, e.meanBias);
      md += line;
      for (const auto* x : {&s, &e}) {
        const bool start = x == &s && !config.lowSunOnly;  // the low-sun fit's start is the shipped constants, mu_0 0
        std::snprintf(line, sizeof(line), "%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%.6g,%.6g,%.6g,%.6g,%s\n",
                      f.group.c_str(), start ? 0.5 : f.a, start ? 0.5 : f.b, start ? 0.5 : f.c, start ? 1.0 : f.d,
                      start ? 0.0 : f.r, start ? 0.0 : f.ra, x == &s ? 0.0 : f.lowSunMu, x->scene.c_str(), x->relRmse,
                      x->noiseCorrected, x->noiseFloor, x->meanBias, x == &s ? "start" : "fit");
        csv += line;
      }
    }
  writeTextFileAtomically(config.outDir / "clouds_calibration.csv", csv);
  if (!result.lowSunSweep.empty()) {
    std::string sweep =
        "group,low_sun_mu,rms_rel_rmse,scene,rel_rmse,rel_rmse_noise_corrected,ref_noise_rel_rmse,mean_bias\n";
    for (const CloudCalibrationSweepPoint& p : result.lowSunSweep)
      for (const CloudCalibrationSceneError& e : p.scenes) {
        std::snprintf(line, sizeof(line), "%s,%.4f,%.6g,%s,%.6g,%.6g,%.6g,%.6g\n", p.group.c_str(), p.lowSunMu,
                      std::sqrt(p.objective), e.scene.c_str(), e.relRmse, e.noiseCorrected, e.noiseFloor, e.meanBias);
        sweep += line;
      }
    writeTextFileAtomically(config.outDir / "clouds_calibration_low_sun.csv", sweep);
  }
  writeTextFileAtomically(config.outDir / "clouds_calibration.md", md);
}

}  // namespace firmament
