#include <gtest/gtest.h>

#include "runtime/error.h"
#include "runtime/vulkan/context.h"
#include "runtime/vulkan/kernel_registry.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using ContextTest = VulkanTest;

TEST_F(ContextTest, ChosenDeviceIsComputeCapableAndDescribed) {
  const vk::DeviceInfo& info = context().info();
  EXPECT_TRUE(info.computeCapable);
  EXPECT_FALSE(info.name.empty());
  EXPECT_FALSE(info.apiVersion.empty());
  EXPECT_GT(info.maxStorageBufferRange, 0u);
  EXPECT_TRUE(context().validationEnabled());
}

TEST_F(ContextTest, ListDevicesIncludesTheChosenDevice) {
  const auto devices = vk::Context::listDevices();
  ASSERT_FALSE(devices.empty());
  ASSERT_LT(context().info().index, devices.size());
  EXPECT_EQ(devices[context().info().index].name, context().info().name);
}

TEST_F(ContextTest, DeviceIndexOutOfRangeIsAClearError) {
  vk::ContextOptions options;
  options.deviceIndex = 999;
  try {
    vk::Context bad(options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--device 999 does not exist"), std::string::npos) << e.what();
  }
}

TEST_F(ContextTest, Int64AtomicsCanBeDisabledForFallbackTests) {
  vk::ContextOptions options;
  options.disableInt64Atomics = true;
  vk::Context withoutAtomics(options);
  EXPECT_FALSE(withoutAtomics.info().int64BufferAtomics);
}

TEST_F(ContextTest, EveryEmbeddedKernelIsSpirv) {
  const auto kernels = vk::embeddedKernels();
  ASSERT_FALSE(kernels.empty());
  for (const vk::EmbeddedKernel& kernel : kernels) {
    ASSERT_GT(kernel.wordCount, 5u) << kernel.name;
    EXPECT_EQ(kernel.words[0], 0x07230203u) << kernel.name;  // SPIR-V magic
    EXPECT_EQ(&vk::findKernel(kernel.name), &kernel);
  }
  EXPECT_THROW(vk::findKernel("no/such_kernel"), Error);
}

}  // namespace
}  // namespace hmb::test

namespace hmb::test {
namespace {

// The messenger must really see errors, or every "zero validation errors" check is empty.
TEST(ValidationMessengerTest, CountsADeliberateError) {
  vk::ContextOptions options;
  options.validation = true;
  vk::Context ctx(options);
  ASSERT_EQ(ctx.validationErrors(), 0u);
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;  // invalid: VUID-VkBufferCreateInfo-size-00912
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(ctx.device(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS && buffer) vkDestroyBuffer(ctx.device(), buffer, nullptr);
  EXPECT_GE(ctx.validationErrors(), 1u);
  ASSERT_FALSE(ctx.validationMessages().empty());
  EXPECT_NE(ctx.validationMessages().front().find("error"), std::string::npos);
}

}  // namespace
}  // namespace hmb::test
