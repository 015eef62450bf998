// What Vulkan's precision rules let a driver return for the operations a kernel cannot make
// exact ("Precision and Operation of SPIR-V Instructions" in the Vulkan specification): a
// test that compares such a result with its C++ reference compares within the rule's bound,
// and names it, so that it holds on any conformant device, not only on lavapipe.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace hmb::test {

// Units in the last place between two finite floats of one sign (0 for equal values).
inline uint32_t ulpDistance(float a, float b) {
  if (a == b) return 0;
  if (!std::isfinite(a) || !std::isfinite(b) || std::signbit(a) != std::signbit(b)) return UINT32_MAX;
  uint32_t ia, ib;
  std::memcpy(&ia, &a, sizeof(ia));
  std::memcpy(&ib, &b, sizeof(ib));
  return ia > ib ? ia - ib : ib - ia;
}

// x / y: 2.5 ULP for |y| in [2^-126, 2^126].
inline constexpr uint32_t kVulkanDivisionUlp = 3;
// sqrt(x): "inherited from 1.0 / inversesqrt(x)", inversesqrt within 2 ULP, so within 2 ULP
// and a division's 2.5 more.
inline constexpr uint32_t kVulkanSqrtUlp = 5;

}  // namespace hmb::test
