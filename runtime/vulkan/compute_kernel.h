// One compute pipeline built from an embedded kernel. Its bindings are buffers in set 0 (storage
// buffers, and uniform texel buffers where a kernel reads 16-byte records through the texture
// path; 2D images only where an engine's images are read or written), and its parameters one
// push-constant block: every kernel follows that shape. The kernel's
// SPIR-V says which binding numbers it declares. A kernel with an address build (its
// groups of buffers bound as tables of device addresses) uses that build where its plain one
// has more bindings than the device allows, or always with ContextOptions::bindByAddress.
// Specialization constants, where a kernel has them, are 32-bit values with ids 0..M-1.
// An embedded kernel's pipeline is made once per context and shared by every ComputeKernel
// that asks for it with the same push-constant size and specialization (kernel_store.h).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hmblur/kernel_builds.h"

namespace hmb::kernels {
struct KernelFacts;
}

namespace hmb::vk {

class Context;
struct EmbeddedKernel;
struct KernelPipeline;

class ComputeKernel {
 public:
  // An embedded kernel, as kernels/manifest.h lists it: kernels::kernel("mblur/tile_max").
  // specialization[i] is the value of constant_id i; constants left out keep the kernel's default.
  ComputeKernel(const Context& context, const kernels::KernelFacts& kernel,
                std::span<const uint32_t> specialization = {});
  // The same by name and push-constant size (a host that disagrees with the SPIR-V is an error).
  ComputeKernel(const Context& context, std::string_view kernelName, uint32_t pushConstantBytes,
                std::span<const uint32_t> specialization = {});
  // The same from SPIR-V compiled at run time, named kernelName in errors.
  ComputeKernel(const Context& context, std::string_view kernelName, const KernelBuilds& builds,
                uint32_t pushConstantBytes, std::span<const uint32_t> specialization = {});
  ~ComputeKernel();
  ComputeKernel(const ComputeKernel&) = delete;
  ComputeKernel& operator=(const ComputeKernel&) = delete;

  const std::string& name() const { return name_; }
  uint32_t storageBufferCount() const;
  // The binding numbers it declares, ascending. An address build keeps its plain build's
  // numbers: each group's table sits at the group's first number, the rest stay unused.
  const std::vector<uint32_t>& bindings() const;
  // Those of bindings() that it reads through a texel view (RGBA32UI), ascending.
  const std::vector<uint32_t>& texelBindings() const;
  bool isTexelBinding(uint32_t index) const;
  // What binding `index` is: a storage buffer, a uniform texel buffer, a sampled image or a
  // storage image.
  VkDescriptorType descriptorType(uint32_t index) const;
  // Whether the address build runs: the passes then bind each group's table, not its buffers.
  bool bindsByAddress() const;
  uint32_t pushConstantBytes() const { return pushConstantBytes_; }
  VkPipeline pipeline() const;
  VkPipelineLayout layout() const;
  VkDescriptorSetLayout setLayout() const;

 private:
  std::shared_ptr<const KernelPipeline> build(const EmbeddedKernel& plain, const EmbeddedKernel* byAddress,
                                              std::span<const uint32_t> specialization) const;

  const Context& context_;
  std::string name_;
  uint32_t pushConstantBytes_ = 0;
  std::shared_ptr<const KernelPipeline> pipeline_;
};

}  // namespace hmb::vk
