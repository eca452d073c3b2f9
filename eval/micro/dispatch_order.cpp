// bench_dispatch_order [width height heavyIterations lightIterations repeats]
// Times a 2D image kernel whose top half is expensive and bottom half cheap (like sky above ground)
// with the tiles in row order and interleaved (shaders/common/dispatch.glsl), plus a uniform-cost
// control. Each figure is the median GPU time (timestamp queries) over the repeats, after a warm-up
// submission that absorbs the JIT compile on lavapipe.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "eval/micro/bench_support.h"
#include "gpu/command.h"
#include "gpu/context.h"
#include "gpu/dispatch.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"

using namespace firmament;
using namespace firmament::gpu;

namespace {

struct Push {
  TileDispatch tiles;
  uint32_t heavyIterations;
  uint32_t lightIterations;
};

using bench::median;

}  // namespace

int main(int argc, char** argv) {
  return bench::runReportingErrors([&]() -> int {
    uint32_t width = argc > 1 ? uint32_t(std::stoul(argv[1])) : 1280;
    uint32_t height = argc > 2 ? uint32_t(std::stoul(argv[2])) : 720;
    uint32_t heavy = argc > 3 ? uint32_t(std::stoul(argv[3])) : 200;
    uint32_t light = argc > 4 ? uint32_t(std::stoul(argv[4])) : 10;
    int repeats = argc > 5 ? std::stoi(argv[5]) : 9;

    ContextOptions options;
    options.device = std::getenv("FIRMAMENT_DEVICE") ? std::getenv("FIRMAMENT_DEVICE") : "";
    Context gpu(options);
    ComputePipeline kernel(
        gpu,
        {.shader = "gpu/uneven_work_bench", .bindings = {BindingType::StorageImage}, .pushConstantSize = sizeof(Push)});
    Image target(
        gpu, {.width = width, .height = height, .format = Format::RGBA16F, .sampled = false, .name = "bench target"});
    std::printf("device: %s\n", gpu.description().c_str());
    const char* threads = std::getenv("LP_NUM_THREADS");
    std::printf("image %ux%u, %u iterations/pixel in the top half, %u in the bottom; median of %d%s%s\n", width, height,
                heavy, light, repeats, threads ? ", LP_NUM_THREADS=" : "", threads ? threads : "");

    struct Case {
      const char* name;
      DispatchOrder order;
      uint32_t heavy, light;
      std::vector<double> ms;
    };
    std::vector<Case> cases = {
        {"uneven, row order", DispatchOrder::RowMajor, heavy, light, {}},
        {"uneven, interleaved", DispatchOrder::Interleaved, heavy, light, {}},
        {"uniform, row order", DispatchOrder::RowMajor, (heavy + light) / 2, (heavy + light) / 2, {}},
        {"uniform, interleaved", DispatchOrder::Interleaved, (heavy + light) / 2, (heavy + light) / 2, {}}};
    std::vector<std::unique_ptr<CommandList>> lists;
    for (Case& c : cases) {
      Push push{tileDispatch(gpu, width, height, c.order), c.heavy, c.light};
      auto list = std::make_unique<CommandList>(gpu);
      list->bind(kernel, {target});
      list->pushConstants(push);
      list->dispatchTiles(push.tiles, "kernel");
      list->submitAndWait();  // warm-up
      lists.push_back(std::move(list));
    }
    // Interleave the cases across repeats so slow drifts (turbo, other load) hit all of them alike.
    for (int r = 0; r < repeats; ++r)
      for (size_t i = 0; i < cases.size(); ++i) {
        lists[i]->submitAndWait();
        cases[i].ms.push_back(lists[i]->timings().at("kernel"));
      }
    for (const Case& c : cases) std::printf("  %-22s %9.2f ms\n", c.name, median(c.ms));
    std::printf("speed-up of interleaving, uneven work: %.2fx; uniform work: %.2fx\n",
                median(cases[0].ms) / median(cases[1].ms), median(cases[2].ms) / median(cases[3].ms));
    if (!lists[0]->timingNote().empty()) std::printf("note: %s\n", lists[0]->timingNote().c_str());
    return kExitOk;
  });
}
