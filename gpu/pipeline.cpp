#include "gpu/pipeline.h"

#include <utility>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/pipeline_cache.h"
#include "gpu/shaders.h"

namespace firmament::gpu {

const char* bindingTypeName(BindingType type) {
  switch (type) {
    case BindingType::StorageBuffer:
      return "storage buffer";
    case BindingType::UniformBuffer:
      return "uniform buffer";
    case BindingType::StorageImage:
      return "storage image";
    case BindingType::SampledImage:
      return "sampled image";
  }
  return "?";
}

namespace {
VkDescriptorType descriptorType(BindingType type) {
  switch (type) {
    case BindingType::StorageBuffer:
      return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingType::UniformBuffer:
      return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingType::StorageImage:
      return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case BindingType::SampledImage:
      return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}
}  // namespace

ComputePipeline::ComputePipeline(Context& context, const PipelineDesc& desc) : context_(&context), desc_(desc) {
  if (desc.pushConstantSize % 4 != 0 || desc.pushConstantSize > context.limits().maxPushConstantsSize)
    throw RuntimeError("pipeline " + desc.shader + ": push-constant size " + std::to_string(desc.pushConstantSize) +
                       " is not a multiple of 4 up to " + std::to_string(context.limits().maxPushConstantsSize));
  std::span<const uint32_t> code = shaderCode(desc.shader);
  VkDevice device = context.device();
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < desc.bindings.size(); ++i)
      bindings.push_back({i, descriptorType(desc.bindings[i]), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    // Push descriptors: resources are written straight into the command buffer, so there is no pool
    // to size and no set to keep alive per frame.
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = uint32_t(bindings.size());
    setInfo.pBindings = bindings.data();
    FIRMAMENT_VK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout_));

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, desc.pushConstantSize};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout_;
    layoutInfo.pushConstantRangeCount = desc.pushConstantSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    FIRMAMENT_VK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout_));

    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = code.size_bytes();
    moduleInfo.pCode = code.data();
    FIRMAMENT_VK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));

    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < desc.specialization.size(); ++i)
      entries.push_back({i, uint32_t(i * sizeof(uint32_t)), sizeof(uint32_t)});
    VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(),
                                        desc.specialization.size() * sizeof(uint32_t), desc.specialization.data()};
    if (!entries.empty()) info.stage.pSpecializationInfo = &specialization;
    info.layout = layout_;
    FIRMAMENT_VK(vkCreateComputePipelines(device, context.pipelineCache().handle(), 1, &info, nullptr, &pipeline_));
    context.pipelineCache().markDirty();
  } catch (...) {
    if (module) vkDestroyShaderModule(device, module, nullptr);
    release();
    throw;
  }
  vkDestroyShaderModule(device, module, nullptr);  // the pipeline keeps what it needs
  context.setObjectName(VK_OBJECT_TYPE_PIPELINE, uint64_t(pipeline_), desc.shader);
}

ComputePipeline::~ComputePipeline() { release(); }

void ComputePipeline::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
  context_ = nullptr;
}

ComputePipeline::ComputePipeline(ComputePipeline&& other) noexcept { *this = std::move(other); }

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    desc_ = std::move(other.desc_);
    setLayout_ = std::exchange(other.setLayout_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
  }
  return *this;
}

}  // namespace firmament::gpu
