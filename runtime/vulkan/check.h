// Turns a failed Vulkan call into an hmb::Error that names the call and the result.
#pragma once

#include <string>

#include <vulkan/vulkan.h>

#include "hmblur/error.h"

namespace hmb::vk {

const char* resultName(VkResult result);

[[noreturn]] void throwVkError(const char* call, VkResult result);

}  // namespace hmb::vk

#define HMB_VK_CHECK(call)                                   \
  do {                                                       \
    const VkResult hmb_vk_result_ = (call);                  \
    if (hmb_vk_result_ != VK_SUCCESS)                        \
      ::hmb::vk::throwVkError(#call, hmb_vk_result_);        \
  } while (0)
