// What a kernel's SPIR-V declares (its descriptor bindings, push-constant block and workgroup
// size), read with SPIRV-Cross, and the check that a device can run it. Pipeline creation
// runs the check, so a kernel that does not fit a device is a one-line error naming the
// kernel and the limit, not a driver failure.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace hmb::vk {

struct EmbeddedKernel;

struct KernelInterface {
  std::vector<uint32_t> storageBufferBindings;  // binding numbers in set 0, ascending
  // Buffers read through a texel view (uniform texel buffers), binding numbers in set 0,
  // ascending: 16-byte records fetched as RGBA32UI texels.
  std::vector<uint32_t> texelBufferBindings;
  // 2D images read with texelFetch and no sampler (GL_EXT_samplerless_texture_functions), and
  // 2D storage images written: an engine's own images (the engine backend's kernels).
  std::vector<uint32_t> sampledImageBindings;
  std::vector<uint32_t> storageImageBindings;
  uint32_t uniformBuffers = 0;
  uint32_t otherDescriptors = 0;     // samplers, other images, acceleration structures (none expected)
  uint32_t highestDescriptorSet = 0;
  uint32_t pushConstantBytes = 0;    // the declared size of the push-constant block, 0 without one
  uint32_t localSize[3] = {1, 1, 1};
  bool usesDeviceAddresses = false;  // PhysicalStorageBufferAddresses: address builds only
};

// Throws hmb::Error when the SPIR-V cannot be read.
KernelInterface reflectKernel(const EmbeddedKernel& kernel);

// Why the kernel does not fit the device (one line: the kernel, what it needs, the limit's
// name and value), or empty when it fits.
std::string whyKernelDoesNotFit(const std::string& kernelName, const KernelInterface& kernel,
                                const VkPhysicalDeviceLimits& limits);

}  // namespace hmb::vk
