#include "gpu/command.h"

#include <algorithm>
#include <chrono>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/memory.h"
#include "gpu/pipeline.h"
#include "gpu/sampler.h"

namespace firmament::gpu {

CommandList::CommandList(Context& context) : context_(context) {
  VkDevice device = context.device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context.queueFamily();
  FIRMAMENT_VK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool_));
  try {
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = pool_;
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    FIRMAMENT_VK(vkAllocateCommandBuffers(device, &allocInfo, &commands_));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    FIRMAMENT_VK(vkCreateFence(device, &fenceInfo, nullptr, &fence_));
  } catch (...) {
    vkDestroyCommandPool(device, pool_, nullptr);
    throw;
  }
  if (!context.timestampsSupported())
    timingNote_ = "the compute queue of " + context.deviceName() +
                  " has no timestamps; timings are wall clock for the whole submission";
}

CommandList::CommandList(Context& context, VkCommandBuffer external) : context_(context), external_(true) {
  if (!external) throw RuntimeError("CommandList: no command buffer given");
  commands_ = external;
  state_ = State::Recording;
  fullMemoryBarrier(commands_);  // the host's writes before (its colour and depth) are visible
}

void CommandList::finish() {
  if (!external_) throw RuntimeError("CommandList::finish is for a host's command buffer");
  if (openGroup_ >= 0) throw RuntimeError("CommandList::finish with an open beginTiming group");
  fullMemoryBarrier(commands_);  // Firmament's writes are visible to the host's commands after
}

CommandList::~CommandList() {
  VkDevice device = context_.device();
  for (VkQueryPool queries : queryPools_) vkDestroyQueryPool(device, queries, nullptr);
  if (external_) return;
  if (fence_) vkDestroyFence(device, fence_, nullptr);
  vkDestroyCommandPool(device, pool_, nullptr);  // frees the command buffer
}

void CommandList::ensureRecording() {
  if (state_ == State::Recording) return;
  if (state_ == State::Executable)
    throw RuntimeError("CommandList: recording after submitAndWait(); call reset() first");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  FIRMAMENT_VK(vkBeginCommandBuffer(commands_, &begin));
  state_ = State::Recording;
  // Writes made before this submission (uploads, earlier lists) are visible to it.
  fullMemoryBarrier(commands_);
}

void CommandList::bind(const ComputePipeline& pipeline, std::initializer_list<Resource> resources) {
  ensureRecording();
  const auto& types = pipeline.desc().bindings;
  const std::string& name = pipeline.name();
  if (resources.size() != types.size())
    throw RuntimeError("pipeline " + name + " has " + std::to_string(types.size()) + " bindings, " +
                       std::to_string(resources.size()) + " resources given");
  std::vector<VkDescriptorBufferInfo> bufferInfos(types.size());
  std::vector<VkDescriptorImageInfo> imageInfos(types.size());
  std::vector<VkWriteDescriptorSet> writes;
  uint32_t binding = 0;
  for (const Resource& resource : resources) {
    BindingType type = types[binding];
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = binding;
    write.descriptorCount = 1;
    auto mismatch = [&](const char* given) {
      return RuntimeError("pipeline " + name + " binding " + std::to_string(binding) + " is a " +
                          bindingTypeName(type) + ", given " + given);
    };
    switch (type) {
      case BindingType::StorageBuffer:
      case BindingType::UniformBuffer: {
        if (!resource.buffer_) throw mismatch("an image");
        BufferUsage needed = type == BindingType::StorageBuffer ? BufferUsage::Storage : BufferUsage::Uniform;
        if (!hasUsage(resource.buffer_->usage(), needed)) throw mismatch("a buffer without that usage");
        bufferInfos[binding] = {resource.buffer_->handle(), 0, VK_WHOLE_SIZE};
        write.descriptorType =
            type == BindingType::StorageBuffer ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        write.pBufferInfo = &bufferInfos[binding];
        break;
      }
      case BindingType::StorageImage:
        if (resource.external_.view && !resource.sampler_) {
          imageInfos[binding] = {VK_NULL_HANDLE, resource.external_.view, resource.external_.layout};
          write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
          write.pImageInfo = &imageInfos[binding];
          break;
        }
        if (!resource.image_ || resource.sampler_) throw mismatch(resource.buffer_ ? "a buffer" : "a sampled image");
        if (!resource.image_->desc().storage) throw mismatch("an image without storage usage");
        imageInfos[binding] = {VK_NULL_HANDLE, resource.image_->storageView(resource.level_), VK_IMAGE_LAYOUT_GENERAL};
        write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        write.pImageInfo = &imageInfos[binding];
        break;
      case BindingType::SampledImage:
        if (resource.external_.view && resource.sampler_) {
          imageInfos[binding] = {resource.sampler_->handle(), resource.external_.view, resource.external_.layout};
          write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
          write.pImageInfo = &imageInfos[binding];
          break;
        }
        if (!resource.image_ || !resource.sampler_) throw mismatch("no sampler");
        if (!resource.image_->desc().sampled) throw mismatch("an image without sampled usage");
        imageInfos[binding] = {resource.sampler_->handle(), resource.image_->view(), VK_IMAGE_LAYOUT_GENERAL};
        write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        write.pImageInfo = &imageInfos[binding];
        break;
    }
    writes.push_back(write);
    ++binding;
  }
  vkCmdBindPipeline(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  if (!writes.empty())
    context_.cmdPushDescriptorSet(commands_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0,
                                  uint32_t(writes.size()), writes.data());
  boundPipeline_ = &pipeline;
}

void CommandList::pushConstants(const void* data, uint32_t size) {
  ensureRecording();
  if (!boundPipeline_) throw RuntimeError("CommandList::pushConstants before bind()");
  if (size != boundPipeline_->desc().pushConstantSize)
    throw RuntimeError("pipeline " + boundPipeline_->name() + " takes " +
                       std::to_string(boundPipeline_->desc().pushConstantSize) + " bytes of push constants, " +
                       std::to_string(size) + " given");
  vkCmdPushConstants(commands_, boundPipeline_->layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, size, data);
}

void CommandList::dispatch(uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ, std::string_view label) {
  ensureRecording();
  if (!boundPipeline_) throw RuntimeError("CommandList::dispatch before bind()");
  const uint32_t* limit = context_.limits().maxComputeWorkGroupCount;
  if (groupsX > limit[0] || groupsY > limit[1] || groupsZ > limit[2])
    throw RuntimeError("dispatch of " + boundPipeline_->name() + " exceeds maxComputeWorkGroupCount");
  if (groupsX == 0 || groupsY == 0 || groupsZ == 0) return;
  int range = label.empty() ? -1 : int(beginRange(label));
  vkCmdDispatch(commands_, groupsX, groupsY, groupsZ);
  if (range >= 0) endRange(uint32_t(range));
}

void CommandList::dispatchTiles(const TileDispatch& tiles, std::string_view label) {
  GroupCount groups = tileGroupCount(tiles);
  dispatch(groups.x, groups.y, 1, label);
}

void CommandList::beginTiming(std::string_view label) {
  ensureRecording();
  if (openGroup_ >= 0) throw RuntimeError("CommandList::beginTiming(" + std::string(label) + ") inside another group");
  openGroup_ = int(beginRange(label));
}

void CommandList::endTiming() {
  if (openGroup_ < 0) throw RuntimeError("CommandList::endTiming without beginTiming");
  endRange(uint32_t(openGroup_));
  openGroup_ = -1;
}

void CommandList::barrier() {
  ensureRecording();
  fullMemoryBarrier(commands_);
}

uint32_t CommandList::writeTimestamp(VkPipelineStageFlagBits stage) {
  uint32_t pool = queryCount_ / kQueriesPerPool;
  uint32_t slot = queryCount_ % kQueriesPerPool;
  if (slot == 0) {  // first query of a pool in this recording: make one if needed, reset it in-stream
    if (pool == queryPools_.size()) {
      VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      info.queryCount = kQueriesPerPool;
      VkQueryPool queries = VK_NULL_HANDLE;
      FIRMAMENT_VK(vkCreateQueryPool(context_.device(), &info, nullptr, &queries));
      queryPools_.push_back(queries);
    }
    vkCmdResetQueryPool(commands_, queryPools_[pool], 0, kQueriesPerPool);
  }
  vkCmdWriteTimestamp(commands_, stage, queryPools_[pool], slot);
  return queryCount_++;
}

uint32_t CommandList::beginRange(std::string_view label) {
  TimedRange range;
  range.label = std::string(label);
  // Top of pipe: the time the range's first command starts, once earlier work (and barriers) allow.
  if (context_.timestampsSupported() && !external_)
    range.beginQuery = writeTimestamp(VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
  ranges_.push_back(std::move(range));
  return uint32_t(ranges_.size() - 1);
}

void CommandList::endRange(uint32_t rangeIndex) {
  // Bottom of pipe: written once every earlier command has finished.
  if (context_.timestampsSupported())
    ranges_[rangeIndex].endQuery = writeTimestamp(VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
}

void CommandList::submitAndWait() {
  if (external_) throw RuntimeError("CommandList: a host's command buffer is submitted by the host");
  if (state_ == State::Initial) ensureRecording();  // an empty list still submits (and times) nothing
  if (state_ == State::Recording) {
    if (openGroup_ >= 0) throw RuntimeError("CommandList::submitAndWait with an open beginTiming group");
    fullMemoryBarrier(commands_);  // results visible to the host and to later submissions
    FIRMAMENT_VK(vkEndCommandBuffer(commands_));
    state_ = State::Executable;
  }
  VkDevice device = context_.device();
  VkSubmitInfo submitInfo{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submitInfo.commandBufferCount = 1;
  submitInfo.pCommandBuffers = &commands_;
  FIRMAMENT_VK(vkResetFences(device, 1, &fence_));
  auto start = std::chrono::steady_clock::now();
  context_.submit(submitInfo, fence_);
  FIRMAMENT_VK(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX));
  submitMilliseconds_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  passTimings_.clear();
  if (!context_.timestampsSupported()) {
    passTimings_.push_back({"submit (wall clock)", submitMilliseconds_, 1});
    return;
  }
  collectTimings(true);
}

bool CommandList::readTimings() {
  if (!external_) throw RuntimeError("CommandList::readTimings is for a host's command buffer");
  passTimings_.clear();
  return context_.timestampsSupported() && collectTimings(false);
}

bool CommandList::collectTimings(bool wait) {
  VkDevice device = context_.device();
  std::vector<uint64_t> ticks(queryCount_);
  for (uint32_t first = 0; first < queryCount_; first += kQueriesPerPool) {
    uint32_t count = std::min(kQueriesPerPool, queryCount_ - first);
    const VkResult r = vkGetQueryPoolResults(device, queryPools_[first / kQueriesPerPool], 0, count,
                                             count * sizeof(uint64_t), ticks.data() + first, sizeof(uint64_t),
                                             VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
    if (r == VK_NOT_READY) return false;
    FIRMAMENT_VK(r);
  }
  uint32_t bits = context_.timestampValidBits();
  uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
  for (const TimedRange& range : ranges_) {
    uint64_t elapsed = (ticks[range.endQuery] - ticks[range.beginQuery]) & mask;  // survives one wrap
    double ms = double(elapsed) * context_.timestampPeriodNs() * 1e-6;
    auto found = std::find_if(passTimings_.begin(), passTimings_.end(),
                              [&](const PassTiming& t) { return t.label == range.label; });
    if (found == passTimings_.end()) {
      passTimings_.push_back({range.label, ms, 1});
    } else {
      found->milliseconds += ms;
      ++found->count;
    }
  }
  return true;
}

void CommandList::reset() {
  if (state_ != State::Initial) FIRMAMENT_VK(vkResetCommandBuffer(commands_, 0));
  state_ = State::Initial;
  queryCount_ = 0;
  ranges_.clear();
  openGroup_ = -1;
  boundPipeline_ = nullptr;
  passTimings_.clear();
  submitMilliseconds_ = 0.0;
}

std::map<std::string, double> CommandList::timings() const {
  std::map<std::string, double> out;
  for (const PassTiming& t : passTimings_) out[t.label] = t.milliseconds;
  return out;
}

}  // namespace firmament::gpu
