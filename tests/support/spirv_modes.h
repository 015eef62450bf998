// What a SPIR-V module declares, read from its words (the binary's layout: a 5-word header,
// then instructions whose first word holds their word count and opcode).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace hmb::test {

// True when the module declares SignedZeroInfNanPreserve for 32-bit floats on an entry point
// (kernels/shared/float_controls.glsl).
inline bool keepsNanAndInfinity(std::span<const uint32_t> words) {
  constexpr uint32_t kOpExecutionMode = 16, kSignedZeroInfNanPreserve = 4461, kHeaderWords = 5;
  for (size_t i = kHeaderWords; i < words.size();) {
    const uint32_t count = words[i] >> 16, opcode = words[i] & 0xffffu;
    if (count == 0 || i + count > words.size()) return false;
    if (opcode == kOpExecutionMode && count == 4 && words[i + 2] == kSignedZeroInfNanPreserve && words[i + 3] == 32u)
      return true;
    i += count;
  }
  return false;
}

}  // namespace hmb::test
