#include "runtime/vulkan/kernel_variants.h"

#include <vector>

#include "hmblur/error.h"
#include "kernels/manifest.h"

namespace hmb::vk {

KernelVariants::KernelVariants(const Context& context, const kernels::KernelFacts& kernel)
    : context_(context), name_(kernel.name), pushConstantBytes_(kernel.pushBytes) {}

KernelVariants::~KernelVariants() = default;

const ComputeKernel& KernelVariants::with(std::initializer_list<bool> switches) const {
  if (switches.size() > 32) throw Error(name_ + ": more than 32 specialization switches");
  uint32_t bits = 0;
  std::vector<uint32_t> specialization;
  for (const bool on : switches) {
    bits |= uint32_t(on) << specialization.size();
    specialization.push_back(on ? 1u : 0u);
  }
  std::unique_ptr<ComputeKernel>& kernel = built_[bits];
  if (!kernel) kernel = std::make_unique<ComputeKernel>(context_, name_, pushConstantBytes_, specialization);
  return *kernel;
}

}  // namespace hmb::vk
