// bench_aerial_perspective [--repeats N] [--rounds N [--cheap-clouds]] [--set /path=value]... [--heatmap OUT.png]
// [SCENE.json ...] The clouds' aerial perspective, error against time (docs/atmosphere.md, "Aerial-perspective
// volume"): each scene (default scenes/cumulus.json) is rendered with the air in front of the clouds
// from the volume (several sizes), from the per-pixel march (8, 16, 64 steps) and without it; every
// frame is compared with the per-pixel march of 256 steps (and the 64-step one) by the relative RMSE
// of the image's luminance over the cloud pixels (the reference's cloud transmittance < 0.95). The
// cloud march is the same in every frame (deterministic jitter), so the differences are the air's.
// With --repeats N > 0, also the median GPU time of clouds/render_clouds + sky/aerial_perspective_volume
// over N frames after a warm-up (on a shared CPU, alternate runs: bench_sky_frame does one mode).
// --rounds N: timing only, interleaved: N rounds, each rendering off, march 8, volume 32^3 and volume
// 64x64x32 once (after one warm-up round), so that the load of a shared machine drifts over all of
// them alike; prints per variant the median and range of clouds/render_clouds + the volume pass.
// --cheap-clouds makes the cloud march itself cheap (8 view steps, 1 light step, 1 octave) so the
// air's share of the pass shows.
// --heatmap: the default volume's relative luminance error against the reference as a PNG heat map
// (yellow = 1 %; grey: not a cloud pixel), for the last scene.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_metrics.h"
#include "core/scene.h"
#include "eval/micro/bench_support.h"
#include "gpu/context.h"
#include "sky/sky_renderer.h"

using namespace firmament;

namespace {

struct Variant {
  std::string name;
  std::function<void(SkyRenderOptions&)> apply;
};

std::vector<Variant> variants() {
  auto march = [](int steps) {
    return [steps](SkyRenderOptions& o) {
      o.clouds.aerialPerspective = AerialPerspective::March;
      o.clouds.aerialPerspectiveSteps = steps;
    };
  };
  auto volume = [](int c, int r, int n, int s) {
    return [=](SkyRenderOptions& o) {
      o.clouds.aerialPerspective = AerialPerspective::Volume;
      o.aerialPerspective.columns = c;
      o.aerialPerspective.rows = r;
      o.aerialPerspective.slices = n;
      o.aerialPerspective.stepsPerSlice = s;
    };
  };
  return {{"off", [](SkyRenderOptions& o) { o.clouds.aerialPerspective = AerialPerspective::Off; }},
          {"march 8", march(8)},
          {"march 16", march(16)},
          {"march 64", march(64)},
          {"volume 32x32x32 (default)", volume(32, 32, 32, 1)},
          {"volume 32x32x32, 2 steps/slice", volume(32, 32, 32, 2)},
          {"volume 16x16x16", volume(16, 16, 16, 1)},
          {"volume 16x16x32", volume(16, 16, 32, 1)},
          {"volume 32x32x16", volume(32, 32, 16, 1)},
          {"volume 32x32x64", volume(32, 32, 64, 1)},
          {"volume 32x64x32", volume(32, 64, 32, 1)},
          {"volume 64x64x32", volume(64, 64, 32, 1)},
          {"volume 32x32x32, D 32 km", [=](SkyRenderOptions& o) {
             volume(32, 32, 32, 1)(o);
             o.aerialPerspective.maxDistance_m = 32000.0;
           }}};
}

double passMs(const RenderResult& r, const std::string& label) {
  double ms = 0.0;
  for (const auto& t : r.timings)
    if (t.label == label) ms += t.milliseconds;
  return ms;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::runReportingErrors([&]() -> int {
    int repeats = 0, rounds = 0;
    bool cheapClouds = false;
    std::string heatmap;
    std::vector<std::string> scenes, overrides;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--repeats" && i + 1 < argc)
        repeats = std::stoi(argv[++i]);
      else if (a == "--set" && i + 1 < argc)
        overrides.push_back(argv[++i]);
      else if (a == "--heatmap" && i + 1 < argc)
        heatmap = argv[++i];
      else if (a == "--rounds" && i + 1 < argc)
        rounds = std::stoi(argv[++i]);
      else if (a == "--cheap-clouds")
        cheapClouds = true;
      else
        scenes.push_back(a);
    }
    if (scenes.empty()) scenes.push_back("scenes/cumulus.json");
    gpu::ContextOptions options;
    options.device = std::getenv("FIRMAMENT_DEVICE") ? std::getenv("FIRMAMENT_DEVICE") : "";
    gpu::Context context(options);
    SkyRenderer renderer(context);
    std::printf("device: %s\n", context.description().c_str());
    if (rounds > 0) {
      const Scene scene = Scene::load(scenes.front(), overrides);
      std::vector<Variant> timed;
      for (const Variant& v : variants())
        if (v.name == "off" || v.name == "march 8" || v.name == "volume 32x32x32 (default)" ||
            v.name == "volume 64x64x32")
          timed.push_back(v);
      std::vector<std::vector<double>> ms(timed.size()), volumeMs(timed.size());
      for (int round = -1; round < rounds; ++round)
        for (size_t v = 0; v < timed.size(); ++v) {
          SkyRenderOptions o;
          if (cheapClouds) {
            o.clouds.viewSteps = 8;
            o.clouds.lightSteps = 1;
          }
          timed[v].apply(o);
          const RenderResult r = renderer.render(scene, o);
          if (round < 0) continue;  // warm-up (pipelines, first touch)
          ms[v].push_back(passMs(r, "clouds/render_clouds") + passMs(r, "sky/aerial_perspective_volume"));
          volumeMs[v].push_back(passMs(r, "sky/aerial_perspective_volume"));
        }
      std::printf("%s%s, %d interleaved rounds: clouds/render_clouds + sky/aerial_perspective_volume (ms)\n",
                  scene.source().c_str(), cheapClouds ? " (cheap clouds: 8 view steps, 1 light step)" : "", rounds);
      for (size_t v = 0; v < timed.size(); ++v) {
        const auto [lo, hi] = std::minmax_element(ms[v].begin(), ms[v].end());
        std::printf("  %-32s median %8.1f  range %8.1f - %8.1f   (volume pass median %.2f)\n", timed[v].name.c_str(),
                    bench::median(ms[v]), *lo, *hi, bench::median(volumeMs[v]));
      }
      return kExitOk;
    }
    for (const std::string& path : scenes) {
      const Scene scene = Scene::load(path, overrides);
      SkyRenderOptions base;
      // ms: the median of clouds/render_clouds and of sky/aerial_perspective_volume
      const auto run = [&](const std::function<void(SkyRenderOptions&)>& apply, double* ms) {
        SkyRenderOptions o = base;
        apply(o);
        RenderResult r = renderer.render(scene, o);
        if (ms && repeats > 0) {
          std::vector<double> clouds, volume;
          for (int i = 0; i < repeats; ++i) {
            r = renderer.render(scene, o);
            clouds.push_back(passMs(r, "clouds/render_clouds"));
            volume.push_back(passMs(r, "sky/aerial_perspective_volume"));
          }
          ms[0] = bench::median(clouds);
          ms[1] = bench::median(volume);
        }
        return r;
      };
      const RenderResult reference = run(
          [](SkyRenderOptions& o) {
            o.clouds.aerialPerspective = AerialPerspective::March;
            o.clouds.aerialPerspectiveSteps = 256;
          },
          nullptr);
      const RenderResult fine = run(
          [](SkyRenderOptions& o) {
            o.clouds.aerialPerspective = AerialPerspective::March;
            o.clouds.aerialPerspectiveSteps = 64;
          },
          nullptr);
      std::vector<float> cloudMask(reference.clouds.pixelCount());
      size_t cloudPixels = 0;
      for (size_t i = 0; i < cloudMask.size(); ++i) {
        cloudMask[i] = reference.clouds.pixels[4 * i + 3] < 0.95f ? 1.0f : 0.0f;
        cloudPixels += cloudMask[i] > 0.0f;
      }
      std::printf("\n%s (%dx%d, %zu cloud pixels; reference: the per-pixel air march, 256 steps)\n",
                  scene.source().c_str(), reference.image.width, reference.image.height, cloudPixels);
      std::printf("  %-32s %12s %12s %12s %s\n", "aerial perspective", "rel RMSE", "vs march 64", "max rel err",
                  repeats > 0 ? "  clouds ms  volume ms" : "");
      for (const Variant& v : variants()) {
        double ms[2] = {0.0, 0.0};
        const RenderResult r = run(v.apply, ms);
        const ImageMetrics m = compareImages(r.image, reference.image, cloudMask);
        const ImageMetrics f = compareImages(r.image, fine.image, cloudMask);
        double maxRel = 0.0;
        for (float e : relativeLuminanceError(r.image, reference.image, cloudMask))
          if (std::isfinite(e)) maxRel = std::max(maxRel, double(e));
        if (!heatmap.empty() && v.name == "volume 32x32x32 (default)")
          writeErrorHeatmapPng(heatmap, r.image, reference.image, 0.01, cloudMask);
        char time[48] = "";
        if (repeats > 0) std::snprintf(time, sizeof(time), "%11.1f %10.2f", ms[0], ms[1]);
        std::printf("  %-32s %12.3e %12.3e %12.3e %s\n", v.name.c_str(), m.luminance.relativeRmse,
                    f.luminance.relativeRmse, maxRel, time);
      }
    }
    return kExitOk;
  });
}
