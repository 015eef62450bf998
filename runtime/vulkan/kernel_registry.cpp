#include "runtime/vulkan/kernel_registry.h"

#include <string>

#include "hmblur/error.h"

namespace hmb::vk {

const EmbeddedKernel* findKernelIfBuilt(std::string_view name) {
  for (const EmbeddedKernel& kernel : embeddedKernels())
    if (kernel.name == name) return &kernel;
  return nullptr;
}

const EmbeddedKernel& findKernel(std::string_view name) {
  if (const EmbeddedKernel* kernel = findKernelIfBuilt(name)) return *kernel;
  throw Error("kernel '" + std::string(name) + "' is not built into this binary");
}

const KernelSource* findKernelSource(std::string_view path) {
  for (const KernelSource& source : kernelSources())
    if (source.path == path) return &source;
  return nullptr;
}

}  // namespace hmb::vk
