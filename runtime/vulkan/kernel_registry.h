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

// The GLSL text of a kernel or of a file kernels include, by its path in the source tree
// ("kernels/reveal/reveal_background.comp", "bvh/bvh_layout.h"), for kernels compiled again at
// run time (runtime/vulkan/glsl_compiler.h).
struct KernelSource {
  std::string_view path;
  std::string_view text;
};
// Defined in the generated source table.
const std::span<const KernelSource> kernelSources();
// nullptr when there is no such file.
const KernelSource* findKernelSource(std::string_view path);

// The suffix of a kernel's second build whose groups of buffers are bound as tables of device
// addresses (cmake/EmbedKernels.cmake, HMB_BIND_BY_ADDRESS).
inline constexpr std::string_view kByAddressSuffix = "#by-address";

}  // namespace hmb::vk
