#include "runtime/vulkan/check.h"

#include <string>

namespace hmb::vk {

const char* resultName(VkResult result) {
  switch (result) {
#define HMB_RESULT_CASE(r) \
  case r:                  \
    return #r;
    HMB_RESULT_CASE(VK_SUCCESS)
    HMB_RESULT_CASE(VK_NOT_READY)
    HMB_RESULT_CASE(VK_TIMEOUT)
    HMB_RESULT_CASE(VK_INCOMPLETE)
    HMB_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    HMB_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    HMB_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    HMB_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    HMB_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    HMB_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    HMB_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    HMB_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    HMB_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    HMB_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    HMB_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    HMB_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    HMB_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    HMB_RESULT_CASE(VK_ERROR_UNKNOWN)
#undef HMB_RESULT_CASE
    default:
      return "VkResult (unnamed)";
  }
}

void throwVkError(const char* call, VkResult result) {
  std::string message = std::string("Vulkan call failed with ") + resultName(result) + ": " + call;
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
    message = std::string("out of memory (") + resultName(result) + ") in " + call +
              "; try a smaller image or scene";
  else if (result == VK_ERROR_DEVICE_LOST)
    message = std::string("the Vulkan device was lost (VK_ERROR_DEVICE_LOST) in ") + call;
  throw Error(message);
}

}  // namespace hmb::vk
