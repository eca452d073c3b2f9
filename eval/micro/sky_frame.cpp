// bench_sky_frame [SCENE.json] [width height repeats] [/json/path=value ...]
// Times the frame passes of a scene (default: the built-in default scene) at a size,
// rendered `repeats` times by one SkyRenderer after a warm-up render (tables, JIT compile, first
// touch of the frame's memory). Prints the median GPU time (timestamp queries) of every pass. Trailing
// arguments of the form /path=value override scene fields (as `firmament render --set`), e.g.
// `bench_sky_frame scenes/cumulus.json 640 360 9 /clouds/aerial_perspective=march`.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/scene.h"
#include "eval/micro/bench_support.h"
#include "gpu/context.h"
#include "sky/sky_renderer.h"

using namespace firmament;

using bench::median;

int main(int argc, char** argv) {
  return bench::runReportingErrors([&]() -> int {
    int arg = 1;
    std::string scenePath;
    if (argc > 1 && std::string(argv[1]).find(".json") != std::string::npos) scenePath = argv[arg++];
    const std::string width = argc > arg ? argv[arg] : "1280";
    const std::string height = argc > arg + 1 ? argv[arg + 1] : "720";
    const int repeats = argc > arg + 2 ? std::stoi(argv[arg + 2]) : 9;
    std::vector<std::string> overrides = {"/camera/width=" + width, "/camera/height=" + height};
    for (int i = arg + 3; i < argc; ++i) overrides.push_back(argv[i]);
    const Scene scene = scenePath.empty() ? Scene::parse(clearSkyDefaultSceneText(), kDefaultSceneName, overrides)
                                          : Scene::load(scenePath, overrides);

    gpu::ContextOptions options;
    options.device = std::getenv("FIRMAMENT_DEVICE") ? std::getenv("FIRMAMENT_DEVICE") : "";
    gpu::Context context(options);
    SkyRenderer renderer(context);
    SkyRenderOptions renderOptions;
    renderer.render(scene, renderOptions);  // warm-up
    renderOptions.downloadImages = false;   // keep a GPU busy between frames (its clocks up)
    std::map<std::string, std::vector<double>> passes;
    std::vector<double> frame;
    for (int i = 0; i < repeats; ++i) {
      RenderResult r = renderer.render(scene, renderOptions);
      frame.push_back(r.frameMilliseconds);
      for (const auto& t : r.timings) passes[t.label].push_back(t.milliseconds);
    }
    std::printf("device: %s\nscene %s, %sx%s, median of %d after a warm-up\n", context.description().c_str(),
                scene.source().c_str(), width.c_str(), height.c_str(), repeats);
    for (size_t i = 2; i < overrides.size(); ++i) std::printf("  override %s\n", overrides[i].c_str());
    for (const auto& [label, ms] : passes) std::printf("  %-32s %9.2f ms\n", label.c_str(), median(ms));
    std::printf("  %-32s %9.2f ms\n", "frame (per-frame passes)", median(frame));
    // Each frame in order: a drift (a GPU's clocks settling, a noisy neighbour) shows as a trend.
    std::printf("  frames (ms):");
    for (double ms : frame) std::printf(" %.2f", ms);
    std::printf("\n");
    return kExitOk;
  });
}
