// The kernels a context has made, kept until the context ends: every pass that asks for the
// same embedded kernel with the same push-constant size and specialization shares one
// pipeline. A second trace scene, build pass or renderer on the same device then makes no
// pipeline at all (lavapipe compiles each kernel when it is made, and a trace scene has two
// build passes of several kernels each); a GPU driver's pipeline cache saves the compilation
// but not the objects.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace hmb::vk {

// The Vulkan objects of one compute kernel and what its SPIR-V declared (ComputeKernel).
struct KernelPipeline {
  KernelPipeline(VkDevice device) : device(device) {}
  ~KernelPipeline();
  KernelPipeline(const KernelPipeline&) = delete;
  KernelPipeline& operator=(const KernelPipeline&) = delete;

  VkDevice device;
  std::vector<uint32_t> bindings;       // ascending
  std::vector<uint32_t> texelBindings;  // those of bindings read through a texel view, ascending
  std::vector<uint32_t> sampledImageBindings;  // those that are 2D images read without a sampler
  std::vector<uint32_t> storageImageBindings;  // those that are 2D storage images
  bool bindsByAddress = false;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
};

class KernelStore {
 public:
  // The kernel kept under `key`, made by `make` the first time (a failure keeps nothing).
  std::shared_ptr<const KernelPipeline> find(const std::string& key,
                                             const std::function<std::shared_ptr<const KernelPipeline>()>& make);
  // Releases what the store keeps (before the device goes; kernels still held stay alive).
  void clear();
  size_t size() const;

 private:
  mutable std::mutex mutex_;
  std::unordered_map<std::string, std::shared_ptr<const KernelPipeline>> kernels_;
};

}  // namespace hmb::vk
