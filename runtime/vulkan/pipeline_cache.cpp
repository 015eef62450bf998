#include "runtime/vulkan/pipeline_cache.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "runtime/vulkan/check.h"

namespace hmb::vk {
namespace {

namespace fs = std::filesystem;

// The header every cache's data starts with (Vulkan spec, vkGetPipelineCacheData).
struct CacheHeader {
  uint32_t headerSize;
  uint32_t headerVersion;
  uint32_t vendorID;
  uint32_t deviceID;
  uint8_t pipelineCacheUUID[VK_UUID_SIZE];
};

std::string hex(const uint8_t* bytes, size_t size) {
  static const char digits[] = "0123456789abcdef";
  std::string text;
  for (size_t i = 0; i < size; ++i) {
    text += digits[bytes[i] >> 4];
    text += digits[bytes[i] & 15];
  }
  return text;
}

bool matches(const std::vector<char>& data, const VkPhysicalDeviceProperties& props) {
  if (data.size() < sizeof(CacheHeader)) return false;
  CacheHeader header;
  std::memcpy(&header, data.data(), sizeof(header));
  return header.headerSize >= sizeof(CacheHeader) && header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
         header.vendorID == props.vendorID && header.deviceID == props.deviceID &&
         std::memcmp(header.pipelineCacheUUID, props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

}  // namespace

fs::path PipelineCache::defaultFolder() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "hybrid-mblur";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "hybrid-mblur";
  return {};
}

PipelineCache::PipelineCache(VkDevice device, VkPhysicalDevice physicalDevice, const fs::path& folder)
    : device_(device) {
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(physicalDevice, &props);
  std::vector<char> data;
  if (!folder.empty()) {
    // One file per device and driver build: the cache UUID changes with the driver.
    file_ = folder / ("pipelines-" + hex(props.pipelineCacheUUID, VK_UUID_SIZE) + ".bin");
    std::ifstream in(file_, std::ios::binary);
    data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!matches(data, props)) data.clear();
  }
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  HMB_VK_CHECK(vkCreatePipelineCache(device_, &info, nullptr, &cache_));
}

PipelineCache::~PipelineCache() {
  if (!file_.empty()) {
    size_t size = 0;
    std::vector<char> data;
    if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) == VK_SUCCESS && size > 0) {
      data.resize(size);
      if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) data.clear();
      data.resize(size);
    }
    // Written beside and renamed, so that two programs ending at once never leave half a file.
    std::error_code error;
    fs::create_directories(file_.parent_path(), error);
    const fs::path partial = file_.string() + "." + std::to_string(getpid()) + ".partial";
    if (!data.empty()) {
      std::ofstream(partial, std::ios::binary).write(data.data(), std::streamsize(data.size()));
      fs::rename(partial, file_, error);
      if (error) fs::remove(partial, error);
    }
  }
  vkDestroyPipelineCache(device_, cache_, nullptr);
}

}  // namespace hmb::vk
