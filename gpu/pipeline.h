#pragma once
// A compute pipeline made from a registered shader, the kinds of its descriptor bindings (set 0,
// bindings 0..n-1 in order, filled with push descriptors at record time) and its push-constant size.
// Built through the Context's on-disk pipeline cache, optionally with specialization constants.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace firmament::gpu {

class Context;

enum class BindingType {
  StorageBuffer,  // layout(std430, binding = i) buffer
  UniformBuffer,  // layout(std140, binding = i) uniform
  StorageImage,   // layout(binding = i, rgba32f) uniform image2D / image3D
  SampledImage,   // layout(binding = i) uniform sampler2D / sampler3D (combined image sampler)
};
const char* bindingTypeName(BindingType type);

struct PipelineDesc {
  std::string shader;                 // registry name, "atmosphere/transmittance"
  std::vector<BindingType> bindings;  // binding i of set 0 has type bindings[i]
  uint32_t pushConstantSize = 0;      // bytes, a multiple of 4, at most 128
  // Specialization constants: value i for `layout(constant_id = i)` (32-bit each: uint, int, bool or
  // float bits). The driver compiles the shader with them as constants, so code they switch off is
  // removed; a shader's constants not listed keep their defaults.
  std::vector<uint32_t> specialization;
};

class ComputePipeline {
 public:
  ComputePipeline() = default;
  ComputePipeline(Context& context, const PipelineDesc& desc);
  ~ComputePipeline();
  ComputePipeline(ComputePipeline&& other) noexcept;
  ComputePipeline& operator=(ComputePipeline&& other) noexcept;
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  const PipelineDesc& desc() const { return desc_; }
  const std::string& name() const { return desc_.shader; }

 private:
  void release();
  Context* context_ = nullptr;
  PipelineDesc desc_;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace firmament::gpu
