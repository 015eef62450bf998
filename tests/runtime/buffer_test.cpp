#include <cstdint>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "runtime/vulkan/buffer_group.h"
#include "tests/support/expect_error.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using BufferTest = VulkanTest;

std::vector<uint32_t> randomWords(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> words(count);
  for (auto& w : words) w = rng();
  return words;
}

TEST_F(BufferTest, RoundTripThroughEveryMemoryUse) {
  for (vk::MemoryUse use : {vk::MemoryUse::Device, vk::MemoryUse::Upload, vk::MemoryUse::Readback}) {
    const auto words = randomWords(100003, 7);  // odd size on purpose
    vk::Buffer buffer(context(), words.size() * sizeof(uint32_t), use, "round trip");
    buffer.upload(std::span<const uint32_t>(words));
    EXPECT_EQ(buffer.download<uint32_t>(), words);
  }
}

// Host reads and waits are counted (what the engine backend's tests hold at zero per frame).
TEST_F(BufferTest, ReadsBackAndWaitsAreCounted) {
  vk::Buffer buffer(context(), 64, vk::MemoryUse::Device, "counted");
  const uint64_t readbacks = context().hostReadbacks(), waits = context().hostWaits();
  buffer.download<uint32_t>();
  EXPECT_EQ(context().hostReadbacks(), readbacks + 1);
  context().submitAndWait([](VkCommandBuffer) {});
  EXPECT_GE(context().hostWaits(), waits + 1);
}

// An adopted buffer is bound like any other and left to its owner.
TEST_F(BufferTest, AnAdoptedBufferIsNeverDestroyed) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 256;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer own = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateBuffer(context().device(), &info, nullptr, &own), VK_SUCCESS);
  {
    vk::Buffer adopted = vk::Buffer::adopt(context(), own, 256, "an engine's");
    EXPECT_EQ(adopted.handle(), own);
    EXPECT_EQ(adopted.size(), 256u);
    vk::Buffer moved = std::move(adopted);
    EXPECT_EQ(moved.handle(), own);
  }
  // Still the owner's: destroying it is valid exactly once (the validation layer counts).
  const uint32_t errors = context().validationErrors();
  vkDestroyBuffer(context().device(), own, nullptr);
  EXPECT_EQ(context().validationErrors(), errors);
  expectError([&] { vk::Buffer::adopt(context(), VK_NULL_HANDLE, 16, "none"); }, "VK_NULL_HANDLE");
}

TEST_F(BufferTest, PartialWriteAndReadAtAnOffset) {
  vk::Buffer buffer(context(), 64, vk::MemoryUse::Device, "offsets");
  const std::vector<uint32_t> zeros(16, 0);
  buffer.upload(std::span<const uint32_t>(zeros));
  const uint32_t value = 0xdeadbeef;
  buffer.write(std::as_bytes(std::span<const uint32_t>(&value, 1)), 20);
  const auto words = buffer.download<uint32_t>();
  for (size_t i = 0; i < words.size(); ++i) EXPECT_EQ(words[i], i == 5 ? value : 0u) << i;
}

TEST_F(BufferTest, DeviceBufferCopiesGoThroughAStagingCopyWhenNotMapped) {
  // Whether or not this device maps device memory, the result must be the same.
  const auto words = randomWords(4096, 11);
  vk::Buffer buffer(context(), words.size() * sizeof(uint32_t), vk::MemoryUse::Device, "device");
  buffer.upload(std::span<const uint32_t>(words));
  std::vector<uint32_t> back(100);
  buffer.read(std::as_writable_bytes(std::span<uint32_t>(back)), 400);
  EXPECT_TRUE(std::equal(back.begin(), back.end(), words.begin() + 100));
}

TEST_F(BufferTest, BadSizesAndRangesAreClearErrors) {
  EXPECT_THROW(vk::Buffer(context(), 0, vk::MemoryUse::Device, "empty"), Error);
  const VkDeviceSize tooLarge = VkDeviceSize(context().limits().maxStorageBufferRange) + 1;
  try {
    vk::Buffer huge(context(), tooLarge, vk::MemoryUse::Device, "huge");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("huge"), std::string::npos) << e.what();
  }
  vk::Buffer small(context(), 16, vk::MemoryUse::Device, "small");
  std::vector<std::byte> bytes(32);
  EXPECT_THROW(small.write(bytes), Error);
  EXPECT_THROW(small.read(bytes), Error);
}

// Kernels read some buffers as uniform texel buffers (16-byte records): the view is made once,
// and a buffer that does not fit one is a one-line error naming the limit and the way around it.
TEST_F(BufferTest, TexelViewsAreMadeOnceAndRefusedPastTheDevicesLimit) {
  vk::Buffer records(context(), 64, vk::MemoryUse::Device, "records");
  const VkBufferView view = records.texelView();
  EXPECT_NE(view, VkBufferView(VK_NULL_HANDLE));
  EXPECT_EQ(records.texelView(), view);
  vk::Buffer word(context(), 4, vk::MemoryUse::Device, "one word");
  expectError([&] { word.texelView(); }, "buffer 'one word' holds 0 16-byte records");

  vk::ContextOptions options;
  options.validation = true;
  options.texelBufferLimit = 3;
  vk::Context small(options);
  ASSERT_EQ(small.limits().maxTexelBufferElements, 3u);
  vk::Buffer four(small, 64, vk::MemoryUse::Device, "four records");
  expectError([&] { four.texelView(); },
              "buffer 'four records' holds 4 16-byte records; a texel view of it needs 1 to 3 "
              "(maxTexelBufferElements); --bind-by-address reads it as a storage buffer");
  EXPECT_EQ(small.validationErrors(), 0u);
}

// A group bound by address binds one table of its members' addresses, kept while they stay and
// made again when a member is made anew, so a kernel never reads a freed buffer's address.
TEST_F(BufferTest, AGroupsAddressTableFollowsItsMembers) {
  if (!context().info().bufferDeviceAddress) GTEST_SKIP() << "no buffer device addresses";
  vk::Buffer a(context(), 64, vk::MemoryUse::Device, "a"), b(context(), 64, vk::MemoryUse::Device, "b");
  vk::BufferGroup group;
  const auto tableOf = [&] {
    const vk::Buffer* members[] = {&a, &b};
    vk::Bindings bindings;
    group.bind(bindings, 3, true, members);
    EXPECT_EQ(bindings.size(), 1u);
    EXPECT_EQ(bindings.front().index, 3u);
    return bindings.front().buffer;
  };
  const vk::Buffer* table = tableOf();
  EXPECT_EQ(table->download<uint64_t>(), (std::vector<uint64_t>{a.address(), b.address()}));
  const VkBuffer first = table->handle();
  EXPECT_EQ(tableOf()->handle(), first);  // the same members: the same table
  // b made anew; the old one stays alive, so the new one cannot take its address.
  vk::Buffer replaced(context(), 64, vk::MemoryUse::Device, "new b");
  std::swap(b, replaced);
  table = tableOf();
  EXPECT_EQ(table->download<uint64_t>(), (std::vector<uint64_t>{a.address(), b.address()}));
  // Plain bindings name the members themselves.
  const vk::Buffer* members[] = {&a, &b};
  vk::Bindings plain;
  group.bind(plain, 3, false, members);
  ASSERT_EQ(plain.size(), 2u);
  EXPECT_EQ(plain[1].index, 4u);
  EXPECT_EQ(plain[1].buffer, &b);
}

TEST_F(BufferTest, MoveLeavesTheSourceEmpty) {
  vk::Buffer a(context(), 256, vk::MemoryUse::Device, "moved");
  const VkBuffer handle = a.handle();
  vk::Buffer b = std::move(a);
  EXPECT_EQ(b.handle(), handle);
  EXPECT_EQ(a.handle(), VK_NULL_HANDLE);  // NOLINT(bugprone-use-after-move): checking the moved-from state
}

}  // namespace
}  // namespace hmb::test
