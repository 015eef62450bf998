// Floats as unsigned integers in the same order, so that shared or buffer atomicMin/atomicMax
// on uint compute float minima and maxima (there are no float atomics in core Vulkan).
#ifndef HMB_KERNELS_SHARED_ORDERED_FLOAT_GLSL
#define HMB_KERNELS_SHARED_ORDERED_FLOAT_GLSL

// Positive floats get the sign bit set; negative ones are inverted, so larger magnitudes come
// first. -0 sorts just below +0. NaN must not reach here (the box kernels drop it).
uint orderedUint(float value) {
  const uint bits = floatBitsToUint(value);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

float orderedFloat(uint ordered) {
  return uintBitsToFloat((ordered & 0x80000000u) != 0u ? ordered & 0x7fffffffu : ~ordered);
}

// Identity of atomicMin / atomicMax on ordered values: +inf and -inf.
const uint kOrderedPositiveInfinity = 0xff800000u;
const uint kOrderedNegativeInfinity = 0x007fffffu;

#endif
