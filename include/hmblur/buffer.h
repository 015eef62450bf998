// Storage buffers. Every kernel reads and writes plain buffers (no images): lavapipe has
// 64-bit buffer atomics but no 64-bit image atomics, and buffers keep layouts explicit. Kernels
// that read 16-byte records at per-lane addresses read them through a texel view of the same
// buffer (texelView(): a uniform texel buffer, gathered on CPU devices, cached on GPUs).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace hmb::vk {

class Context;

enum class MemoryUse {
  Device,    // kernel working memory (vk::Context::findDeviceMemoryType); mapped where that is cheap
  Upload,    // host writes, device reads
  Readback,  // device writes, host reads
};

class Buffer {
 public:
  Buffer() = default;
  // Throws hmb::Error before allocating when the size exceeds what the device allows.
  // extraUsage adds to the storage/transfer/indirect usage every buffer has (e.g. vertex input).
  Buffer(const Context& context, VkDeviceSize bytes, MemoryUse use, std::string name,
         VkBufferUsageFlags extraUsage = 0);
  // A buffer someone else made (an engine's): storage-buffer usage, at least `bytes` long. The
  // Buffer binds it and never destroys it; it has no memory of its own to map or count.
  static Buffer adopt(const Context& context, VkBuffer buffer, VkDeviceSize bytes, std::string name);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  // Where kernels reach it through a table of addresses (kernels/shared/glsl_cpp.h); 0 on
  // devices without bufferDeviceAddress.
  VkDeviceAddress address() const { return address_; }
  const std::string& name() const { return name_; }
  const Context& context() const { return *context_; }
  // A view of the whole buffer as RGBA32UI texels (16-byte records), for kernels that read it
  // as a uniform texel buffer; made on first use. Throws hmb::Error when the buffer holds more
  // texels than the device's maxTexelBufferElements.
  VkBufferView texelView() const;
  // Host pointer when the memory is host-visible and coherent, else nullptr.
  void* mapped() const { return mapped_; }

  // Host <-> buffer copies; go through a staging buffer when the memory is not mapped.
  void write(std::span<const std::byte> bytes, VkDeviceSize offset = 0);
  void read(std::span<std::byte> bytes, VkDeviceSize offset = 0) const;

  template <class T>
  void upload(std::span<const T> values) {
    write(std::as_bytes(values));
  }
  template <class T>
  std::vector<T> download() const {
    std::vector<T> values(size_ / sizeof(T));
    read(std::as_writable_bytes(std::span<T>(values)));
    return values;
  }

 private:
  void release();

  const Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  VkDeviceSize allocated_ = 0;  // the memory's size (at least size_), counted in the context
  uint32_t heap_ = 0;           // the memory heap it was counted in
  void* mapped_ = nullptr;
  bool readDirectly_ = false;  // mapped and cached, or no cached memory to stage through
  VkDeviceAddress address_ = 0;
  mutable VkBufferView texelView_ = VK_NULL_HANDLE;
  bool adopted_ = false;  // someone else's: never destroyed here
  std::string name_;
};

// A device buffer holding `values`, at least one (value-initialized) element long: Vulkan has
// no empty buffers, and empty arrays (a scene without textures) are valid.
template <class T>
Buffer uploadedBuffer(const Context& context, const std::vector<T>& values, std::string name) {
  const T empty{};
  const std::span<const T> data = values.empty() ? std::span<const T>(&empty, 1) : std::span<const T>(values);
  Buffer buffer(context, data.size_bytes(), MemoryUse::Device, std::move(name));
  buffer.upload(data);
  return buffer;
}

}  // namespace hmb::vk
