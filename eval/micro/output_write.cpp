// bench_output_write [width height repeats]
// What writing a full-screen RGBA32F frame costs per target: no write, a storage image, a storage
// buffer. On lavapipe storage-image stores go through a texel-address path per invocation, which
// made a cheap full-screen pass cost ~70 ms at 1280x720 (docs/gpu.md); this measures the alternative.
// Median GPU time (timestamp queries) over the repeats, after a warm-up (lavapipe's JIT compile).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "eval/micro/bench_support.h"
#include "gpu/buffer.h"
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
  uint32_t mode;
};

using bench::median;

}  // namespace

int main(int argc, char** argv) {
  return bench::runReportingErrors([&]() -> int {
    uint32_t width = argc > 1 ? uint32_t(std::stoul(argv[1])) : 1280;
    uint32_t height = argc > 2 ? uint32_t(std::stoul(argv[2])) : 720;
    int repeats = argc > 3 ? std::stoi(argv[3]) : 9;

    ContextOptions options;
    options.device = std::getenv("FIRMAMENT_DEVICE") ? std::getenv("FIRMAMENT_DEVICE") : "";
    Context gpu(options);
    ComputePipeline kernel(gpu, {.shader = "gpu/output_write_bench",
                                 .bindings = {BindingType::StorageImage, BindingType::StorageBuffer},
                                 .pushConstantSize = sizeof(Push)});
    Image image(gpu,
                {.width = width, .height = height, .format = Format::RGBA32F, .sampled = false, .name = "bench image"});
    Buffer buffer(gpu, VkDeviceSize(width) * height * 16, BufferUsage::Storage, MemoryLocation::Device, "bench buffer");
    std::printf("device: %s\nframe %ux%u RGBA32F, median of %d\n", gpu.description().c_str(), width, height, repeats);

    const char* names[] = {"no write", "storage image", "storage buffer"};
    std::vector<std::unique_ptr<CommandList>> lists;
    std::vector<std::vector<double>> ms(3);
    for (uint32_t mode = 0; mode < 3; ++mode) {
      Push push{tileDispatch(gpu, width, height, DispatchOrder::Auto), mode};
      auto list = std::make_unique<CommandList>(gpu);
      list->bind(kernel, {image, buffer});
      list->pushConstants(push);
      list->dispatchTiles(push.tiles, "kernel");
      list->submitAndWait();  // warm-up
      lists.push_back(std::move(list));
    }
    for (int r = 0; r < repeats; ++r)
      for (uint32_t mode = 0; mode < 3; ++mode) {
        lists[mode]->submitAndWait();
        ms[mode].push_back(lists[mode]->timings().at("kernel"));
      }
    for (uint32_t mode = 0; mode < 3; ++mode) std::printf("  %-16s %9.2f ms\n", names[mode], median(ms[mode]));
    if (!lists[0]->timingNote().empty()) std::printf("note: %s\n", lists[0]->timingNote().c_str());
    return kExitOk;
  });
}
