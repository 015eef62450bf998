// The per-pixel jitter of the motion blur kernels: an integer hash of (pixel, seed), the same on
// every device, shared with the C++ reference (kernels/shared/glsl_cpp.h).
#ifndef HMB_KERNELS_MBLUR_MBLUR_HASH_H
#define HMB_KERNELS_MBLUR_MBLUR_HASH_H

#include "../shared/glsl_cpp.h"

HMB_GPU_BEGIN

HMB_SHARED uint mblurHash(uint x, uint y, uint seed) {
  uint h = x * 0x9E3779B1u + y * 0x85EBCA77u + seed * 0xC2B2AE3Du + 0x27D4EB2Fu;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return h;
}

// [0, 1) from the top 24 bits: exact in float.
HMB_SHARED float unitFromHash(uint h) { return float(h >> 8) * (1.0f / 16777216.0f); }

// The next value of a hash sequence (for a second and third random number per pixel).
HMB_SHARED uint nextHash(uint h) { return mblurHash(h, 0x68E31DA4u, 0x1B56C4E9u); }

HMB_GPU_END

#endif
