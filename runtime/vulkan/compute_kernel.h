// One compute pipeline built from an embedded kernel. Its bindings are storage buffers
// 0..N-1 in set 0, and its parameters one push-constant block: every kernel follows that shape.
// Specialization constants, where a kernel has them, are 32-bit values with ids 0..M-1.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace hmb::vk {

class Context;

class ComputeKernel {
 public:
  // specialization[i] is the value of constant_id i; constants left out keep the kernel's default.
  ComputeKernel(const Context& context, std::string_view kernelName, uint32_t storageBufferCount,
                uint32_t pushConstantBytes, std::span<const uint32_t> specialization = {});
  ~ComputeKernel();
  ComputeKernel(const ComputeKernel&) = delete;
  ComputeKernel& operator=(const ComputeKernel&) = delete;

  const std::string& name() const { return name_; }
  uint32_t storageBufferCount() const { return storageBufferCount_; }
  uint32_t pushConstantBytes() const { return pushConstantBytes_; }
  VkPipeline pipeline() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkDescriptorSetLayout setLayout() const { return setLayout_; }

 private:
  void release();

  const Context& context_;
  std::string name_;
  uint32_t storageBufferCount_ = 0;
  uint32_t pushConstantBytes_ = 0;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace hmb::vk
