// The GPU runtime on the machine's device (lavapipe on a machine with no GPU): device choice, memory
// round trips, kernels, timing, pipeline cache, and error paths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "core/error.h"
#include "gpu/buffer.h"
#include "gpu/command.h"
#include "gpu/context.h"
#include "gpu/dispatch.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/pipeline_cache.h"
#include "gpu/sampler.h"
#include "tests/support/gpu_test.h"

namespace firmament::gpu {
namespace {

class GpuRuntimeTest : public test::GpuTest {};

TEST_F(GpuRuntimeTest, ListsDevicesAndDescribesTheChosenOne) {
  auto devices = listDevices();
  ASSERT_FALSE(devices.empty());
  for (const auto& d : devices) {
    EXPECT_FALSE(d.name.empty());
    EXPECT_FALSE(d.driver.empty());
  }
  Context& gpu = context();
  EXPECT_FALSE(gpu.deviceName().empty());
  EXPECT_NE(gpu.description().find(gpu.deviceName()), std::string::npos);
  EXPECT_EQ(gpu.isCpu(), gpu.deviceType() == DeviceType::Cpu);
  // A GPU is preferred over the CPU whenever one is usable.
  bool anyGpu = false;
  for (const auto& d : devices) anyGpu |= d.type != DeviceType::Cpu && d.apiVersion >= VK_API_VERSION_1_3;
  if (!anyGpu) {
    EXPECT_TRUE(gpu.isCpu());
  }
  std::printf("device: %s\n", gpu.description().c_str());
}

TEST_F(GpuRuntimeTest, ValidationFollowsTheEnvironment) {
  EXPECT_EQ(context().validationEnabled(), validationRequestedByEnvironment());
}

TEST(GpuDeviceSelection, BadNameIsInputErrorListingDevices) {
  ContextOptions options;
  options.device = "no-such-device-xyz";
  options.validation = false;
  options.persistentPipelineCache = false;
  try {
    Context gpu(options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("no-such-device-xyz"), std::string::npos) << message;
    EXPECT_NE(message.find(listDevices().front().name), std::string::npos) << message;
  }
  options.device = "999";
  EXPECT_THROW(Context{options}, InputError);
}

TEST(GpuDeviceSelection, SelectsByIndexAndCaseInsensitiveName) {
  auto devices = listDevices();
  ContextOptions options;
  options.validation = false;
  options.persistentPipelineCache = false;
  for (const auto& d : devices) {
    if (d.apiVersion < VK_API_VERSION_1_3) continue;
    options.device = std::to_string(d.index);
    EXPECT_EQ(Context(options).deviceName(), d.name);
    std::string upper = d.name.substr(0, 4);
    for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
    options.device = upper;
    EXPECT_NE(Context(options).deviceName().find(d.name.substr(0, 4)), std::string::npos);
  }
}

TEST(GpuValidation, MissingLayerIsRuntimeErrorNamingThePackage) {
  // Point the loader at an empty layer folder; it re-reads the variable on every enumeration.
  auto empty = test::scratchDir("no-layers");
  const char* previous = std::getenv("VK_LAYER_PATH");
  std::string saved = previous ? previous : "";
  setenv("VK_LAYER_PATH", empty.c_str(), 1);
  ContextOptions options;
  options.validation = true;
  options.persistentPipelineCache = false;
  std::string message;
  try {
    Context gpu(options);
  } catch (const RuntimeError& e) {
    message = e.what();
  }
  if (previous)
    setenv("VK_LAYER_PATH", saved.c_str(), 1);
  else
    unsetenv("VK_LAYER_PATH");
  EXPECT_NE(message.find("vulkan-validationlayers"), std::string::npos) << message;
}

TEST_F(GpuRuntimeTest, BufferRoundTripDeviceAndHost) {
  for (MemoryLocation location : {MemoryLocation::Device, MemoryLocation::Host}) {
    std::vector<uint32_t> values(10007);
    std::iota(values.begin(), values.end(), 12345u);
    Buffer buffer(context(), values.size() * 4, BufferUsage::Storage | BufferUsage::Uniform, location, "round trip");
    buffer.upload(values);
    EXPECT_EQ(buffer.download<uint32_t>(), values);
    // A partial write at an offset leaves the rest alone.
    std::vector<uint32_t> patch = {1, 2, 3};
    buffer.upload(patch, 8);
    auto back = buffer.download<uint32_t>();
    EXPECT_EQ(back[1], values[1]);
    EXPECT_EQ(back[2], 1u);
    EXPECT_EQ(back[4], 3u);
    EXPECT_EQ(back[5], values[5]);
    EXPECT_THROW(buffer.upload(patch, buffer.size() - 4), RuntimeError);
  }
}

TEST_F(GpuRuntimeTest, Image2DRoundTripEveryFormat) {
  for (Format format :
       {Format::RGBA32F, Format::RGBA16F, Format::RG32F, Format::RG16F, Format::R32F, Format::R16F, Format::RGBA8}) {
    SCOPED_TRACE(formatName(format));
    Image image(context(), {.width = 37, .height = 19, .format = format, .name = "round trip 2D"});
    std::vector<float> values(image.texelCount() * channelCount(format));
    // Values exact in every format: multiples of 1/255 in [0, 1] survive 8-bit and half.
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(i % 256) / 255.0f;
    image.uploadFloats(values);
    auto back = image.downloadFloats();
    ASSERT_EQ(back.size(), values.size());
    double tolerance = format == Format::RGBA16F || format == Format::RG16F || format == Format::R16F ? 1e-3 : 1e-6;
    for (size_t i = 0; i < values.size(); ++i) ASSERT_NEAR(back[i], values[i], tolerance) << i;
  }
}

TEST_F(GpuRuntimeTest, Image3DRoundTrip) {
  Image volume(context(), {.width = 9, .height = 7, .depth = 5, .format = Format::RGBA32F, .name = "round trip 3D"});
  EXPECT_TRUE(volume.is3D());
  std::vector<float> values(volume.texelCount() * 4);
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i) * 0.5f - 100.0f;
  volume.uploadFloats(values);
  EXPECT_EQ(volume.downloadFloats(), values);
}

struct FillPush {
  float scale;
  float offset;
  uint32_t count;
};

// Specialization constants reach the shader: the defaults without any, the given values with them
// (a float by its bits, an int, a bool), and two pipelines of one shader keep their own.
TEST_F(GpuRuntimeTest, SpecializationConstantsReachTheShader) {
  Context& gpu = context();
  const uint32_t count = 1000;
  auto run = [&](std::vector<uint32_t> constants) {
    ComputePipeline kernel(gpu, {.shader = "gpu/specialization_test",
                                 .bindings = {BindingType::StorageBuffer},
                                 .pushConstantSize = sizeof(uint32_t),
                                 .specialization = std::move(constants)});
    Buffer values(gpu, count * 4, BufferUsage::Storage, MemoryLocation::Device, "specialized");
    CommandList list(gpu);
    list.bind(kernel, {values});
    list.pushConstants(count);
    list.dispatch((count + 63) / 64, 1, 1, "specialized");
    list.submitAndWait();
    return values.download<float>();
  };
  const float scale = 0.25f;
  uint32_t scaleBits = 0;
  std::memcpy(&scaleBits, &scale, sizeof(scaleBits));
  const std::vector<float> defaults = run({});
  const std::vector<float> scaled = run({scaleBits, uint32_t(int32_t(-7))});
  const std::vector<float> negated = run({scaleBits, 3u, 1u});
  for (uint32_t i = 0; i < count; i += 37) {
    ASSERT_EQ(defaults[i], float(i)) << i;
    ASSERT_EQ(scaled[i], float(i) * 0.25f - 7.0f) << i;
    ASSERT_EQ(negated[i], -(float(i) * 0.25f + 3.0f)) << i;
  }
}

TEST_F(GpuRuntimeTest, FillKernelAndTimestamps) {
  Context& gpu = context();
  ComputePipeline fill(gpu, {.shader = "gpu/fill_buffer_test",
                             .bindings = {BindingType::StorageBuffer},
                             .pushConstantSize = sizeof(FillPush)});
  const uint32_t count = 100003;
  Buffer values(gpu, count * 4, BufferUsage::Storage, MemoryLocation::Device, "fill");
  CommandList list(gpu);
  FillPush push{0.5f, -3.0f, count};
  list.bind(fill, {values});
  list.pushConstants(push);
  list.dispatch((count + 63) / 64, 1, 1, "fill");
  list.barrier();
  list.beginTiming("group");
  list.dispatch((count + 63) / 64, 1, 1, "fill");
  list.endTiming();
  list.submitAndWait();
  auto result = values.download<float>();
  for (uint32_t i = 0; i < count; i += 997) ASSERT_EQ(result[i], float(i) * 0.5f - 3.0f) << i;
  ASSERT_EQ(result[count - 1], float(count - 1) * 0.5f - 3.0f);

  auto timings = list.timings();
  ASSERT_EQ(timings.size(), 2u) << list.timingNote();
  for (const auto& [label, ms] : timings) {
    EXPECT_TRUE(std::isfinite(ms)) << label;
    EXPECT_GT(ms, 0.0) << label;
    EXPECT_LT(ms, 60e3) << label;
  }
  EXPECT_EQ(list.passTimings().front().label, "fill");
  EXPECT_EQ(list.passTimings().front().count, 2u);
  EXPECT_GT(list.submitMilliseconds(), 0.0);

  // The same recording runs again; recording more needs reset().
  list.submitAndWait();
  EXPECT_EQ(list.timings().size(), 2u);
  EXPECT_THROW(list.dispatch(1), RuntimeError);
  list.reset();
  push.offset = 7.0f;
  list.bind(fill, {values});
  list.pushConstants(push);
  list.dispatch((count + 63) / 64);
  list.submitAndWait();
  EXPECT_EQ(values.download<float>()[10], 12.0f);
  EXPECT_TRUE(list.timings().empty());
}

struct FillImagePush {
  TileDispatch tiles;
  float base;
};

TEST_F(GpuRuntimeTest, FillImageKernelThroughTiles) {
  Context& gpu = context();
  ComputePipeline fill(gpu, {.shader = "gpu/fill_image_test",
                             .bindings = {BindingType::StorageImage},
                             .pushConstantSize = sizeof(FillImagePush)});
  for (DispatchOrder order : {DispatchOrder::RowMajor, DispatchOrder::Interleaved}) {
    Image image(gpu, {.width = 131, .height = 45, .format = Format::RGBA32F, .name = "filled"});
    FillImagePush push{tileDispatch(gpu, image.width(), image.height(), order), 42.0f};
    CommandList list(gpu);
    list.bind(fill, {image});
    list.pushConstants(push);
    list.dispatchTiles(push.tiles, "fill image");
    list.submitAndWait();
    auto texels = image.downloadFloats();
    for (uint32_t y = 0; y < image.height(); ++y)
      for (uint32_t x = 0; x < image.width(); ++x) {
        const float* t = &texels[(size_t(y) * image.width() + x) * 4];
        ASSERT_EQ(t[0], float(x));
        ASSERT_EQ(t[1], float(y));
        ASSERT_EQ(t[2], float(x + image.width() * y));
        ASSERT_EQ(t[3], 42.0f);
      }
  }
}

TEST_F(GpuRuntimeTest, SampledTexturesAtTexelCentres) {
  Context& gpu = context();
  ComputePipeline sample(gpu, {.shader = "gpu/sample_test",
                               .bindings = {BindingType::SampledImage, BindingType::SampledImage,
                                            BindingType::StorageBuffer, BindingType::StorageBuffer},
                               .pushConstantSize = 4});
  Image flat(gpu, {.width = 4, .height = 3, .format = Format::RGBA32F, .storage = false, .name = "2D"});
  Image volume(gpu, {.width = 2, .height = 3, .depth = 4, .format = Format::R32F, .name = "3D"});
  std::vector<float> flatValues(flat.texelCount() * 4), volumeValues(volume.texelCount());
  std::iota(flatValues.begin(), flatValues.end(), 0.0f);
  std::iota(volumeValues.begin(), volumeValues.end(), 100.0f);
  flat.uploadFloats(flatValues);
  volume.uploadFloats(volumeValues);
  Sampler nearest(gpu, Filter::Nearest, AddressMode::Clamp);
  Sampler linearWrap(gpu, {.filter = Filter::Linear, .u = AddressMode::Repeat});

  // Sample 0: the centre of 2D texel (1, 2) and of 3D texel (1, 2, 3). Sample 1: halfway between 2D
  // texels (0, 0) and (1, 0), and the centre of 3D texel (0, 0, 0).
  std::vector<float> coordinates = {1.5f / 4, 2.5f / 3, 0, 0, 1.5f / 2, 2.5f / 3, 3.5f / 4, 0,
                                    1.0f / 4, 0.5f / 3, 0, 0, 0.5f / 2, 0.5f / 3, 0.5f / 4, 0};
  Buffer input(gpu, coordinates.size() * 4, BufferUsage::Storage);
  input.upload(coordinates);
  Buffer output(gpu, 4 * 4 * 4, BufferUsage::Storage);
  CommandList list(gpu);
  uint32_t count = 1;
  list.bind(sample, {{flat, nearest}, {volume, nearest}, input, output});
  list.pushConstants(count);
  list.dispatch(1);
  list.barrier();
  count = 2;
  list.bind(sample, {{flat, linearWrap}, {volume, nearest}, input, output});
  list.pushConstants(count);
  list.dispatch(1);
  list.submitAndWait();
  auto results = output.download<float>();
  size_t texel = (2 * 4 + 1) * 4;  // 2D texel (1, 2)
  for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(results[c], flatValues[texel + c]);
  EXPECT_FLOAT_EQ(results[4], volumeValues[(3 * 3 + 2) * 2 + 1]);  // R32F reads as (v, 0, 0, 1)
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(results[8 + c], 0.5f * (flatValues[c] + flatValues[4 + c]), 1e-2f);
  EXPECT_FLOAT_EQ(results[12], volumeValues[0]);
}

TEST_F(GpuRuntimeTest, WrongResourcesAreRejected) {
  Context& gpu = context();
  EXPECT_THROW(ComputePipeline(gpu, {.shader = "gpu/no_such_shader"}), RuntimeError);
  ComputePipeline fill(gpu, {.shader = "gpu/fill_buffer_test",
                             .bindings = {BindingType::StorageBuffer},
                             .pushConstantSize = sizeof(FillPush)});
  Image image(gpu, {.width = 8, .height = 8, .name = "wrong"});
  Buffer uniformOnly(gpu, 64, BufferUsage::Uniform, MemoryLocation::Host);
  CommandList list(gpu);
  EXPECT_THROW(list.bind(fill, {image}), RuntimeError);
  EXPECT_THROW(list.bind(fill, {uniformOnly}), RuntimeError);
  EXPECT_THROW(list.bind(fill, {}), RuntimeError);
  list.bind(fill, {Buffer(gpu, 64, BufferUsage::Storage)});  // temporary: fine since never submitted
  EXPECT_THROW(list.pushConstants(uint32_t(1)), RuntimeError);
}

TEST(GpuPipelineCache, WrittenOnExitReadBackAndCorruptFilesIgnored) {
  auto dir = test::scratchDir("pipeline-cache");
  ContextOptions options;
  options.cacheDir = dir;
  options.validation = validationRequestedByEnvironment();
  std::filesystem::path file;
  {
    Context gpu(options);
    ComputePipeline fill(gpu, {.shader = "gpu/fill_buffer_test",
                               .bindings = {BindingType::StorageBuffer},
                               .pushConstantSize = sizeof(FillPush)});
    file = gpu.pipelineCache().file();
    EXPECT_FALSE(gpu.pipelineCache().loadedFromDisk());
    EXPECT_TRUE(gpu.validationMessages().empty());
  }
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_EQ(file.parent_path(), dir);
  {
    Context gpu(options);
    EXPECT_TRUE(gpu.pipelineCache().loadedFromDisk());
  }
  for (std::string junk : {std::string("garbage"), std::string(4096, '\xff'), std::string()}) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << junk;
    Context gpu(options);
    EXPECT_FALSE(gpu.pipelineCache().loadedFromDisk());
    ComputePipeline fill(gpu, {.shader = "gpu/fill_buffer_test",
                               .bindings = {BindingType::StorageBuffer},
                               .pushConstantSize = sizeof(FillPush)});
    EXPECT_TRUE(gpu.validationMessages().empty());
  }
  // No temporary files left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().extension(), ".vkcache") << entry.path();
}

TEST(GpuPipelineCache, DefaultFolderFollowsTheEnvironment) {
  const char* saved = std::getenv("FIRMAMENT_CACHE_DIR");
  std::string previous = saved ? saved : "";
  setenv("FIRMAMENT_CACHE_DIR", "/tmp/firmament-cache-test", 1);
  EXPECT_EQ(defaultCacheDir(), std::filesystem::path("/tmp/firmament-cache-test"));
  unsetenv("FIRMAMENT_CACHE_DIR");
  if (std::getenv("XDG_CACHE_HOME") && *std::getenv("XDG_CACHE_HOME")) {
    EXPECT_EQ(defaultCacheDir(), std::filesystem::path(std::getenv("XDG_CACHE_HOME")) / "firmament");
  }
  if (saved) setenv("FIRMAMENT_CACHE_DIR", previous.c_str(), 1);
}

}  // namespace
}  // namespace firmament::gpu
