// The compiled kernels kept on disk across runs: a VkPipelineCache per device, read when a
// context starts and written back when it ends, under $XDG_CACHE_HOME/hybrid-mblur (or
// ~/.cache/hybrid-mblur). On drivers that keep compiled pipelines in their cache data (most GPU
// drivers) a run's first frames then skip compilation; Mesa 22.3's lavapipe stores only the
// header, and compiles each kernel at its first dispatch whatever the cache holds.
#pragma once

#include <filesystem>

#include <vulkan/vulkan.h>

namespace hmb::vk {

class PipelineCache {
 public:
  // `folder` empty: a cache in memory only. A file whose header names another device or driver
  // version is not used (the driver would reject it anyway) and is replaced at the end.
  PipelineCache(VkDevice device, VkPhysicalDevice physicalDevice, const std::filesystem::path& folder);
  ~PipelineCache();  // writes the cache back (a failure to write costs only the next run's time)
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  const std::filesystem::path& file() const { return file_; }  // empty: not kept on disk

  // $XDG_CACHE_HOME/hybrid-mblur, else $HOME/.cache/hybrid-mblur; empty when neither is set.
  static std::filesystem::path defaultFolder();

 private:
  VkDevice device_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::filesystem::path file_;
};

}  // namespace hmb::vk
