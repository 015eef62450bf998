// Base fixture of every test that touches Vulkan: one context per test process with the
// Khronos validation layer on, and any validation error during a test fails that test. Its
// device profile is HMB_DEVICE_PROFILE's (auto where unset), so a whole run can force one.
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "hmblur/context.h"

namespace hmb::test {

class VulkanTest : public ::testing::Test {
 public:
  static vk::Context& context() {
    static std::unique_ptr<vk::Context> shared = [] {
      vk::ContextOptions options;
      options.validation = true;
      options.synchronizationValidation = true;
      options.deviceProfile = vk::deviceProfileChoiceFromEnvironment();
      return std::make_unique<vk::Context>(options);
    }();
    return *shared;
  }

 protected:
  void SetUp() override { errorsBefore_ = context().validationErrors(); }
  void TearDown() override {
    const uint32_t errors = context().validationErrors() - errorsBefore_;
    if (errors == 0) return;
    std::string all;
    for (const std::string& message : context().validationMessages()) all += message + "\n";
    ADD_FAILURE() << errors << " Vulkan validation error(s) during this test:\n" << all;
  }

 private:
  uint32_t errorsBefore_ = 0;
};

}  // namespace hmb::test
