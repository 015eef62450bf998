#version 450
// The linear builder's first pass (linear_bvh_layout.h), one workgroup: the bounds of the
// primitives' centroids, each centroid's 30-bit Morton code in them, and a stable radix sort of
// the codes, 4 bits a pass, each lane a run of them. The sorted codes and the primitive order
// end in the first halves of their buffers. One group suffices for a top level (at most
// HMB_LINEAR_BVH_MAX_PRIMITIVES instances); a lane counts, scans and scatters its run in order,
// so equal codes keep the order of their primitives.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "linear_bvh_layout.h"

layout(local_size_x = HMB_LINEAR_SORT_GROUP) in;
layout(std430, binding = HMB_LINEAR_SORT_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
// Each pass reads what every lane of the last one wrote.
layout(std430, binding = HMB_LINEAR_SORT_BINDING_CODES) coherent buffer Codes { uint codes[]; };
layout(std430, binding = HMB_LINEAR_SORT_BINDING_PRIMITIVES) coherent buffer Primitives { uint primitives[]; };
layout(push_constant) uniform Params { LinearBvhParams params; };

const uint kLanes = HMB_LINEAR_SORT_GROUP;
const uint kDigits = 1u << HMB_LINEAR_SORT_DIGIT_BITS;
shared uint digitCounts[kDigits * kLanes];  // digit-major: [digit * lanes + lane]
shared uint laneSums[kLanes];
shared vec3 lanesLow[kLanes];
shared vec3 lanesHigh[kLanes];

// A box's centre, or the origin where the box is empty or not finite (it still gets a leaf).
vec3 centroidOf(uint primitive) {
  const vec3 c = 0.5 * (boxes[primitive].min.xyz + boxes[primitive].max.xyz);
  return all(lessThanEqual(boxes[primitive].min.xyz, boxes[primitive].max.xyz)) && !any(isinf(c)) && !any(isnan(c))
             ? c : vec3(0.0);
}

void main() {
  const uint n = params.primitiveCount, lane = gl_LocalInvocationIndex;
  const uint run = (n + kLanes - 1u) / kLanes, begin = min(lane * run, n), end = min(begin + run, n);

  // The centroids' bounds.
  vec3 low = vec3(uintBitsToFloat(0x7f7fffffu)), high = -low;
  for (uint i = begin; i < end; ++i) {
    const vec3 c = centroidOf(i);
    low = min(low, c);
    high = max(high, c);
  }
  lanesLow[lane] = low;
  lanesHigh[lane] = high;
  barrier();
  for (uint other = 0u; other < kLanes; ++other) {
    low = min(low, lanesLow[other]);
    high = max(high, lanesHigh[other]);
  }
  // A cell per 1/1024 of each axis; a flat axis puts every centroid in cell 0.
  const vec3 extent = high - low;
  precise const vec3 scale = mix(vec3(0.0), 1024.0 / extent, greaterThan(extent, vec3(0.0)));
  for (uint i = begin; i < end; ++i) {
    precise const vec3 t = (centroidOf(i) - low) * scale;
    codes[i] = mortonCode(uvec3(clamp(t, vec3(0.0), vec3(1023.0))));
    primitives[i] = i;
  }

  // Eight passes of 4 bits, from the first halves to the second and back.
  for (uint pass = 0u; pass < HMB_LINEAR_SORT_PASSES; ++pass) {
    const uint from = (pass & 1u) * n, to = n - from, shift = pass * HMB_LINEAR_SORT_DIGIT_BITS;
    memoryBarrierBuffer();
    barrier();
    for (uint d = 0u; d < kDigits; ++d) digitCounts[d * kLanes + lane] = 0u;
    for (uint i = begin; i < end; ++i) ++digitCounts[((codes[from + i] >> shift) & (kDigits - 1u)) * kLanes + lane];
    barrier();
    // Exclusive sums over (digit, lane): a lane sums kDigits entries, lane 0 the lanes' sums.
    uint sum = 0u;
    for (uint k = 0u; k < kDigits; ++k) sum += digitCounts[lane * kDigits + k];
    laneSums[lane] = sum;
    barrier();
    if (lane == 0u) {
      uint total = 0u;
      for (uint other = 0u; other < kLanes; ++other) {
        const uint s = laneSums[other];
        laneSums[other] = total;
        total += s;
      }
    }
    barrier();
    uint offset = laneSums[lane];
    for (uint k = 0u; k < kDigits; ++k) {
      const uint count = digitCounts[lane * kDigits + k];
      digitCounts[lane * kDigits + k] = offset;
      offset += count;
    }
    barrier();
    for (uint i = begin; i < end; ++i) {
      const uint code = codes[from + i];
      const uint place = digitCounts[((code >> shift) & (kDigits - 1u)) * kLanes + lane]++;
      codes[to + place] = code;
      primitives[to + place] = primitives[from + i];
    }
  }
}
