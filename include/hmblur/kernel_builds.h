// What a ComputeKernel is built from where a user's code goes into a kernel (passes::HitShading).
#pragma once

#include <cstdint>
#include <vector>

namespace hmb::vk {

// A kernel's SPIR-V made at run time (glsl_compiler.h): its plain build and, where the kernel
// has one, its address build (empty: none).
struct KernelBuilds {
  std::vector<uint32_t> plain, byAddress;
};

}  // namespace hmb::vk
