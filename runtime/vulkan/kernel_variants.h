// One embedded kernel built per combination of its on/off specialization constants (ids 0..N-1,
// VkBool32 each), each build made the first time a frame asks for it. A kernel compiled for the
// frame's switches has none of the others' code, which a CPU device would run under its lanes'
// mask whatever the switches said.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {

class KernelVariants {
 public:
  KernelVariants(const Context& context, const kernels::KernelFacts& kernel);
  ~KernelVariants();

  // The build whose constant i is switches[i] (at most 32 switches).
  const ComputeKernel& with(std::initializer_list<bool> switches) const;

 private:
  const Context& context_;
  std::string name_;
  uint32_t pushConstantBytes_;
  mutable std::map<uint32_t, std::unique_ptr<ComputeKernel>> built_;  // by the switches' bits
};

}  // namespace hmb::vk
