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

}  // namespace hmb::vk
