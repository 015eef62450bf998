// The SPIR-V of every kernel, compiled at build time and embedded (cmake/EmbedKernels.cmake).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace hmb::vk {

struct EmbeddedKernel {
  std::string_view name;  // path under kernels/ without ".comp", e.g. "output/encode_display"
  const uint32_t* words;
  size_t wordCount;
};

// Defined in the generated kernel table.
const std::span<const EmbeddedKernel> embeddedKernels();

// Throws hmb::Error naming the kernel when it was not built in.
const EmbeddedKernel& findKernel(std::string_view name);
// nullptr when not built in.
const EmbeddedKernel* findKernelIfBuilt(std::string_view name);

// The suffix of a kernel's second build whose groups of buffers are bound as tables of device
// addresses (cmake/EmbedKernels.cmake, HMB_BIND_BY_ADDRESS).
inline constexpr std::string_view kByAddressSuffix = "#by-address";

}  // namespace hmb::vk
