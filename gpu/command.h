#pragma once
// Records compute work into one command buffer, submits it and waits, then reports per-pass GPU
// time from timestamp queries.
//
//   CommandList list(context);
//   list.bind(pipeline, {inputBuffer, outputImage, {lut, linearClamp}});
//   list.pushConstants(push);
//   list.dispatchTiles(push.tiles, "sky");     // or dispatch(x, y, z, "label")
//   list.barrier();                            // before a pass that reads what this one wrote
//   ...
//   list.submitAndWait();
//   list.timings();                            // {"sky": 3.2, ...} in milliseconds
//
// Resources are bound with push descriptors, so they must outlive the submission only. After
// submitAndWait() the same recording can be submitted again (benchmarks); reset() starts a new one.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/dispatch.h"

namespace firmament::gpu {

class Buffer;
class ComputePipeline;
class Context;
class Image;
class Sampler;

// An image view that is not a gpu::Image (a host application's, embedded mode), in the given layout.
struct ExternalView {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

// One mip level of an image, for a storage binding: {image, MipLevel{k}}.
struct MipLevel {
  uint32_t level = 0;
};

// One descriptor: a buffer (storage or uniform, as the pipeline declares), a storage image (level 0,
// or the level given), or an image with a sampler (every level). Converts implicitly, so bind() reads
// like the shader's binding list.
class Resource {
 public:
  Resource(const Buffer& buffer) : buffer_(&buffer) {}  // NOLINT: implicit on purpose
  Resource(const Image& image) : image_(&image) {}      // NOLINT
  Resource(const Image& image, MipLevel level) : image_(&image), level_(level.level) {}
  Resource(const Image& image, const Sampler& sampler) : image_(&image), sampler_(&sampler) {}
  Resource(ExternalView view) : external_(view) {}  // NOLINT: a storage image
  Resource(ExternalView view, const Sampler& sampler) : sampler_(&sampler), external_(view) {}

 private:
  friend class CommandList;
  const Buffer* buffer_ = nullptr;
  const Image* image_ = nullptr;
  const Sampler* sampler_ = nullptr;
  uint32_t level_ = 0;
  ExternalView external_;
};

struct PassTiming {
  std::string label;
  double milliseconds = 0.0;  // summed over every dispatch or group with this label
  uint32_t count = 0;         // how many were summed
};

class CommandList {
 public:
  explicit CommandList(Context& context);
  // Records into a host's command buffer, in the recording state (embedded mode): a full memory
  // barrier first, and no submission (submitAndWait() throws; the host submits). finish() ends
  // Firmament's part with a full memory barrier; the buffer stays the host's. Its timestamps are read
  // by readTimings() once the host's submission has finished (the list must live until then).
  CommandList(Context& context, VkCommandBuffer external);
  void finish();
  // A host's command buffer: reads the timings without waiting; false (and no timings) when the
  // queries are not all available (the buffer was not submitted, or has not finished).
  bool readTimings();
  ~CommandList();
  CommandList(const CommandList&) = delete;
  CommandList& operator=(const CommandList&) = delete;

  // Binds the pipeline and resources[i] to binding i; the count and kinds must match the pipeline.
  void bind(const ComputePipeline& pipeline, std::initializer_list<Resource> resources);
  // Push constants of the bound pipeline (size must equal its pushConstantSize).
  void pushConstants(const void* data, uint32_t size);
  template <class T>
  void pushConstants(const T& block) {
    pushConstants(&block, uint32_t(sizeof(T)));
  }

  // A non-empty label times this dispatch; repeated labels add up.
  void dispatch(uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1, std::string_view label = {});
  // A 2D image kernel over tiles (shaders/common/dispatch.glsl); `tiles` must be what was pushed.
  void dispatchTiles(const TileDispatch& tiles, std::string_view label = {});
  // Times everything recorded between the two calls under one label (groups do not nest).
  void beginTiming(std::string_view label);
  void endTiming();

  // Every write before is visible to every read and write after (compute, transfer and host).
  void barrier();

  // Ends the recording (first time), submits, waits, and reads the timestamps.
  void submitAndWait();
  // Forgets the recording and the timings; the next call records afresh.
  void reset();

  // Label -> milliseconds of the last submission.
  std::map<std::string, double> timings() const;
  // The same in first-recorded order, with counts.
  const std::vector<PassTiming>& passTimings() const { return passTimings_; }
  // Wall-clock milliseconds of the last submitAndWait (submit to fence), always available.
  double submitMilliseconds() const { return submitMilliseconds_; }
  // Empty, or why the timings are wall clock instead of GPU timestamps.
  const std::string& timingNote() const { return timingNote_; }

  VkCommandBuffer handle() const { return commands_; }

 private:
  struct TimedRange {
    std::string label;
    uint32_t beginQuery = 0;
    uint32_t endQuery = 0;
  };
  void ensureRecording();
  uint32_t writeTimestamp(VkPipelineStageFlagBits stage);
  uint32_t beginRange(std::string_view label);
  void endRange(uint32_t rangeIndex);
  // The timestamps into passTimings_; wait: block until they are available. False when not waiting
  // and some are not.
  bool collectTimings(bool wait);

  static constexpr uint32_t kQueriesPerPool = 64;

  Context& context_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::vector<VkQueryPool> queryPools_;
  uint32_t queryCount_ = 0;
  std::vector<TimedRange> ranges_;
  int openGroup_ = -1;  // index into ranges_ of the open beginTiming, or -1
  const ComputePipeline* boundPipeline_ = nullptr;
  enum class State { Initial, Recording, Executable } state_ = State::Initial;
  bool external_ = false;
  std::vector<PassTiming> passTimings_;
  double submitMilliseconds_ = 0.0;
  std::string timingNote_;
};

}  // namespace firmament::gpu
