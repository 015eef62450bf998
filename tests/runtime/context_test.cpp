#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/debug/test_pattern.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/kernel_registry.h"
#include "runtime/vulkan/pipeline_cache.h"
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

// Compiled kernels are kept on disk across runs: a file per device and driver build, written
// when the context ends, whose header names that device; one that names another is replaced.
TEST_F(ContextTest, PipelineCacheIsKeptOnDiskPerDevice) {
  const std::filesystem::path folder = std::filesystem::path(testing::TempDir()) / "hmblur_pipeline_cache";
  std::filesystem::remove_all(folder);
  vk::ContextOptions options;
  options.validation = true;
  options.pipelineCacheFolder = folder;
  std::filesystem::path file;
  {
    vk::Context owned(options);
    file = owned.pipelineCache().file();
    EXPECT_EQ(file.parent_path(), folder);
    vk::ComputeKernel kernel(owned, "debug/test_pattern", sizeof(gpu::TestPatternParams));
    EXPECT_EQ(owned.validationErrors(), 0u);
  }
  ASSERT_TRUE(std::filesystem::exists(file));
  std::ifstream in(file, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(data.size(), 16u + VK_UUID_SIZE);
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(context().physicalDevice(), &props);
  uint32_t vendor = 0, device = 0;
  std::memcpy(&vendor, data.data() + 8, 4);
  std::memcpy(&device, data.data() + 12, 4);
  EXPECT_EQ(vendor, props.vendorID);
  EXPECT_EQ(device, props.deviceID);

  // A file of another device or of garbage is not handed to the driver, and is replaced.
  std::ofstream(file, std::ios::binary) << "not a pipeline cache";
  {
    vk::Context again(options);
    vk::ComputeKernel kernel(again, "debug/test_pattern", sizeof(gpu::TestPatternParams));
    EXPECT_EQ(again.validationErrors(), 0u);
  }
  EXPECT_GE(std::filesystem::file_size(file), 16u + VK_UUID_SIZE);

  // No folder: nothing written.
  options.pipelineCacheFolder.clear();
  vk::Context inMemory(options);
  EXPECT_TRUE(inMemory.pipelineCache().file().empty());
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
