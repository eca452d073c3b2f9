#pragma once
// GoogleTest fixture for tests that use the GPU: one Context shared by the whole test binary (device
// creation with validation costs ~0.1 s, the first dispatch of each pipeline a JIT compile on lavapipe)
// and a TearDown that fails the test if the validation layer reported anything during it.
// Header-only, so firmament_test_support need not link firmament_gpu; a test folder that includes it
// links firmament_gpu (directly or through its module library).
//
//   class MyPassTest : public firmament::test::GpuTest {};
//   TEST_F(MyPassTest, Works) { gpu::Context& gpu = context(); ... }
#include <gtest/gtest.h>

#include <cerrno>  // program_invocation_short_name: one cache folder per test binary (CTest runs them in parallel)
#include <cstdlib>
#include <memory>
#include <string>

#include "gpu/context.h"
#include "tests/support/test_paths.h"

namespace firmament::test {

class GpuTest : public ::testing::Test {
 public:
  // Validation follows FIRMAMENT_VALIDATION (CTest sets it to 1); the pipeline cache goes to the
  // build tree so tests never touch the user's cache.
  static gpu::Context& context() {
    static std::unique_ptr<gpu::Context> shared = [] {
      gpu::ContextOptions options;
      // A sharded folder's entries (tests/CMakeLists.txt, SHARDS) run the same binary side by side: one
      // folder each, since each clears its own at start and counts the files it adds.
      const char* shard = std::getenv("GTEST_SHARD_INDEX");
      options.cacheDir = scratchDir(std::string("gpu-test-pipeline-cache-") + program_invocation_short_name +
                                    (shard ? std::string("-shard") + shard : std::string()));
      return std::make_unique<gpu::Context>(options);
    }();
    return *shared;
  }

 protected:
  void SetUp() override { context().clearValidationMessages(); }

  void TearDown() override {
    auto messages = context().validationMessages();
    context().clearValidationMessages();
    if (messages.empty()) return;
    std::string text;
    for (const auto& message : messages) text += "\n  " + message;
    ADD_FAILURE() << messages.size() << " Vulkan validation message(s) during this test:" << text;
  }
};

}  // namespace firmament::test
