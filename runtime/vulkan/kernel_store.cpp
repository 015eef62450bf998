#include "runtime/vulkan/kernel_store.h"

namespace hmb::vk {

KernelPipeline::~KernelPipeline() {
  if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
  if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
  if (setLayout) vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
}

std::shared_ptr<const KernelPipeline> KernelStore::find(
    const std::string& key, const std::function<std::shared_ptr<const KernelPipeline>()>& make) {
  // Made under the lock: two threads asking for the same kernel compile it once.
  const std::lock_guard lock(mutex_);
  auto& kept = kernels_[key];
  if (!kept) {
    try {
      kept = make();
    } catch (...) {
      kernels_.erase(key);
      throw;
    }
  }
  return kept;
}

void KernelStore::clear() {
  const std::lock_guard lock(mutex_);
  kernels_.clear();
}

size_t KernelStore::size() const {
  const std::lock_guard lock(mutex_);
  return kernels_.size();
}

}  // namespace hmb::vk
