// Lets one header declare structs and constants for both GLSL kernels and C++ hosts, so the
// two sides cannot drift. Shared structs use only 4-byte scalars, vec2/ivec2/uvec2 at 8-byte
// offsets and vec4/uvec4/mat4 at 16-byte offsets, which lay out the same in std430 and C++;
// every shared struct is checked with HMB_CHECK_SIZE on the C++ side.
//
// Small pure functions both sides run (hashes, clip planes, dispatch folding) are written once
// in the common subset of the two languages and declared HMB_SHARED (inline in C++).
//
// A table of device addresses (a group of buffers that travel together: the trace scene, the
// shading scene, an image layer) declares each member HMB_REFERENCE(Type) at an 8-byte offset:
// a GL_EXT_buffer_reference block type in GLSL, the buffer's VkDeviceAddress in C++.
#ifndef HMB_KERNELS_SHARED_GLSL_CPP_H
#define HMB_KERNELS_SHARED_GLSL_CPP_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#define HMB_GPU_BEGIN                \
  namespace hmb::gpu {               \
  using uint = uint32_t;             \
  using vec2 = glm::vec2;            \
  using vec3 = glm::vec3;            \
  using vec4 = glm::vec4;            \
  using ivec2 = glm::ivec2;          \
  using uvec2 = glm::uvec2;          \
  using uvec3 = glm::uvec3;          \
  using uvec4 = glm::uvec4;          \
  using mat4 = glm::mat4;            \
  using glm::abs;                    \
  using glm::clamp;                  \
  using glm::floatBitsToUint;        \
  using glm::isinf;                  \
  using glm::isnan;                  \
  using glm::max;                    \
  using glm::min;                    \
  using glm::normalize;              \
  using glm::sqrt;                   \
  using glm::packHalf2x16;           \
  using glm::packSnorm2x16;          \
  using glm::uintBitsToFloat;        \
  using glm::unpackHalf2x16;         \
  using glm::unpackSnorm2x16;
#define HMB_GPU_END }
#define HMB_REFERENCE(Type) uint64_t
#define HMB_SHARED inline
#define HMB_CHECK_SIZE(type, bytes) static_assert(sizeof(hmb::gpu::type) == (bytes), #type " layout drifted");
#else
// Only address builds (HMB_BIND_BY_ADDRESS) use device addresses: plain builds must run on
// devices without them.
#ifdef HMB_BIND_BY_ADDRESS
#extension GL_EXT_buffer_reference : require
#endif
#define HMB_GPU_BEGIN
#define HMB_GPU_END
#define HMB_REFERENCE(Type) Type
#define HMB_SHARED
#define HMB_CHECK_SIZE(type, bytes)
#endif

// Tables of device addresses exist on the host and in address builds.
#if defined(__cplusplus) || defined(HMB_BIND_BY_ADDRESS)
#define HMB_ADDRESS_TABLES 1
#endif

#endif
