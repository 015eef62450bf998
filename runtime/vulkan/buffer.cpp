#include "hmblur/buffer.h"

#include <utility>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "runtime/vulkan/check.h"

namespace hmb::vk {
namespace {

std::string mib(VkDeviceSize bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

Buffer::Buffer(const Context& context, VkDeviceSize bytes, MemoryUse use, std::string name,
               VkBufferUsageFlags extraUsage)
    : context_(&context), size_(bytes), name_(std::move(name)) {
  if (bytes == 0) throw Error("buffer '" + name_ + "' has size 0");
  const auto& limits = context.limits();
  if (bytes > limits.maxStorageBufferRange)
    throw Error("buffer '" + name_ + "' needs " + mib(bytes) + " but the device allows at most " +
                mib(limits.maxStorageBufferRange) + " per storage buffer; use a smaller image or scene");

  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = bytes;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
               VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | extraUsage;
  const bool addressable = context.info().bufferDeviceAddress;
  if (addressable) info.usage |= VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  const VkDevice device = context.device();
  HMB_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer_));

  try {
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device, buffer_, &req);

    const VkMemoryPropertyFlags hostFlags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = UINT32_MAX;
    switch (use) {
      case MemoryUse::Device:
        type = context.findDeviceMemoryType(req.memoryTypeBits);
        break;
      case MemoryUse::Upload:
        type = context.findMemoryType(req.memoryTypeBits, hostFlags);
        break;
      case MemoryUse::Readback:
        type = context.findMemoryType(req.memoryTypeBits, hostFlags, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        break;
    }
    if (type == UINT32_MAX) throw Error("no memory type fits buffer '" + name_ + "'");

    const auto& memory = context.memoryProperties();
    const uint32_t heap = memory.memoryTypes[type].heapIndex;
    const VkDeviceSize heapSize = memory.memoryHeaps[heap].size;
    // Checked before allocating: past the heap, drivers that overcommit fail later and worse.
    const VkDeviceSize inUse = context.heapInUse(heap);
    if (inUse + req.size > heapSize)
      throw Error("buffer '" + name_ + "' needs " + mib(req.size) + " of device memory, but its " + mib(heapSize) +
                  " heap already holds " + mib(inUse) + "; use a smaller image or scene");

    VkMemoryAllocateFlagsInfo addressFlags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    addressFlags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    if (addressable) alloc.pNext = &addressFlags;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context.allocationType(type);
    HMB_VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &memory_));
    allocated_ = req.size;
    heap_ = heap;
    context.countAllocation(heap_, allocated_);
    HMB_VK_CHECK(vkBindBufferMemory(device, buffer_, memory_, 0));

    const VkMemoryPropertyFlags flags = memory.memoryTypes[type].propertyFlags;
    if ((flags & hostFlags) == hostFlags) HMB_VK_CHECK(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
    if (addressable) {
      VkBufferDeviceAddressInfo addressInfo{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
      addressInfo.buffer = buffer_;
      address_ = vkGetBufferDeviceAddress(device, &addressInfo);
    }
    // Reading mapped memory the host does not cache is slow (VRAM through a BAR): such a buffer
    // is read through a staging copy, where the device has cached memory to copy into.
    const VkMemoryPropertyFlags cached = hostFlags | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    readDirectly_ = (flags & cached) == cached ||
                    ((flags & hostFlags) == hostFlags && context.findMemoryType(req.memoryTypeBits, cached) == UINT32_MAX);
  } catch (...) {
    release();
    throw;
  }
}

Buffer Buffer::adopt(const Context& context, VkBuffer buffer, VkDeviceSize bytes, std::string name) {
  if (!buffer) throw Error("buffer '" + name + "' to adopt is VK_NULL_HANDLE");
  Buffer adopted;
  adopted.context_ = &context;
  adopted.buffer_ = buffer;
  adopted.size_ = bytes;
  adopted.adopted_ = true;
  adopted.name_ = std::move(name);
  return adopted;
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    allocated_ = std::exchange(other.allocated_, 0);
    heap_ = other.heap_;
    mapped_ = std::exchange(other.mapped_, nullptr);
    readDirectly_ = other.readDirectly_;
    address_ = std::exchange(other.address_, 0);
    texelView_ = std::exchange(other.texelView_, VK_NULL_HANDLE);
    adopted_ = std::exchange(other.adopted_, false);
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::release() {
  if (!context_) return;
  const VkDevice device = context_->device();
  if (mapped_) vkUnmapMemory(device, memory_);
  if (texelView_) vkDestroyBufferView(device, texelView_, nullptr);
  if (buffer_ && !adopted_) vkDestroyBuffer(device, buffer_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);
  if (allocated_) context_->countRelease(heap_, allocated_);
  allocated_ = 0;
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  address_ = 0;
  texelView_ = VK_NULL_HANDLE;
  adopted_ = false;
}

VkBufferView Buffer::texelView() const {
  if (texelView_) return texelView_;
  constexpr VkDeviceSize kTexelBytes = 16;  // RGBA32UI
  const VkDeviceSize texels = size_ / kTexelBytes;
  if (texels == 0 || texels > context_->limits().maxTexelBufferElements)
    throw Error("buffer '" + name_ + "' holds " + std::to_string(texels) +
                " 16-byte records; a texel view of it needs 1 to " +
                std::to_string(context_->limits().maxTexelBufferElements) +
                " (maxTexelBufferElements); --bind-by-address reads it as a storage buffer");
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = buffer_;
  info.format = VK_FORMAT_R32G32B32A32_UINT;
  info.offset = 0;
  info.range = texels * kTexelBytes;
  HMB_VK_CHECK(vkCreateBufferView(context_->device(), &info, nullptr, &texelView_));
  return texelView_;
}

void Buffer::write(std::span<const std::byte> bytes, VkDeviceSize offset) {
  if (offset + bytes.size() > size_)
    throw Error("write of " + std::to_string(bytes.size()) + " bytes past the end of buffer '" + name_ + "'");
  if (bytes.empty()) return;
  if (mapped_) {
    std::memcpy(static_cast<std::byte*>(mapped_) + offset, bytes.data(), bytes.size());
    return;
  }
  Buffer staging(*context_, bytes.size(), MemoryUse::Upload, name_ + " (staging)");
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  context_->submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, offset, bytes.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &region);
  });
}

void Buffer::read(std::span<std::byte> bytes, VkDeviceSize offset) const {
  if (offset + bytes.size() > size_)
    throw Error("read of " + std::to_string(bytes.size()) + " bytes past the end of buffer '" + name_ + "'");
  if (bytes.empty()) return;
  context_->countReadback();
  if (mapped_ && readDirectly_) {
    std::memcpy(bytes.data(), static_cast<const std::byte*>(mapped_) + offset, bytes.size());
    return;
  }
  Buffer staging(*context_, bytes.size(), MemoryUse::Readback, name_ + " (readback)");
  context_->submitAndWait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{offset, 0, bytes.size()};
    vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &region);
    VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                         nullptr, 0, nullptr);
  });
  std::memcpy(bytes.data(), staging.mapped(), bytes.size());
}

}  // namespace hmb::vk
