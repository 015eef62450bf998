// Packed BVH nodes (bvh/bvh_layout.h: BvhPackedNode, BvhFrame): what the builder writes and
// traversal reads, half the size of a node of floats. Each bound is a count of steps from its
// tree's frame, rounded outwards, so a packed box always holds the exact one and a ray that
// meets the exact box meets the packed one. The host's twin is bvh/packed_node.cpp.
#ifndef HMB_KERNELS_BVH_PACKED_NODE_GLSL
#define HMB_KERNELS_BVH_PACKED_NODE_GLSL

// The bound `steps` steps from `origin`. Both products are rounded on their own (precise: no
// fused multiply-add), so the builder, traversal and the host all get the same float.
float boundAt(uint steps, float origin, float step) {
  precise const float offset = float(steps) * step;
  precise const float bound = origin + offset;
  return bound;
}

// The frame of a tree whose root box is lo..hi: the lower corner, and a step that reaches the
// upper corner in HMB_BVH_QUANTUM_MAX steps. The scaled difference cannot overflow, and the
// step is widened until its last bound lies at or past the box (rounding may fall short).
BvhFrame frameOf(vec3 lo, vec3 hi) {
  BvhFrame frame;
  frame.origin = vec4(0.0);
  frame.step = vec4(1.0, 1.0, 1.0, 0.0);
  if (any(greaterThan(lo, hi)) || any(isnan(lo)) || any(isnan(hi))) return frame;  // empty: nothing to count
  const float maxFloat = uintBitsToFloat(0x7f7fffffu);
  lo = clamp(lo, vec3(-maxFloat), vec3(maxFloat));
  hi = clamp(hi, vec3(-maxFloat), vec3(maxFloat));
  const float perStep = 1.0 / float(HMB_BVH_QUANTUM_MAX);
  precise vec3 step = (hi * perStep - lo * perStep) * (1.0 + 1.0 / 1024.0);
  for (uint a = 0; a < 3; ++a)
    for (uint i = 0; i < 64u && boundAt(HMB_BVH_QUANTUM_MAX, lo[a], step[a]) < hi[a]; ++i) {
      precise const float doubled = step[a] * 2.0;
      step[a] = doubled + uintBitsToFloat(0x00800000u);  // + the least normal: a zero step grows
    }
  frame.origin = vec4(lo, 0.0);
  frame.step = vec4(step, 0.0);
  return frame;
}

// The most steps whose bound is at or below x (0 when none is). boundAt rises with the steps,
// so a binary search finds it; the quotient (x - origin) / step names it to within a step,
// and where the bounds around that guess confirm it (nearly always) two compares pick the
// answer from those three steps, else the search runs over all of them. (Lavapipe runs both
// sides of a branch, so an unrolled search would cost its sixteen halvings every time; the
// loop costs one of an invocation's loop iterations where no lane needs it.)
uint stepsBelow(float x, float origin, float step) {
  if (step == 0.0) return x >= origin ? HMB_BVH_QUANTUM_MAX : 0u;  // a flat axis: every bound is the origin
  const float guess = (x - origin) / step;
  if (guess >= 0.0 && guess <= float(HMB_BVH_QUANTUM_MAX)) {  // NaN and far guesses search it all
    const uint g = uint(guess), near = g > 0u ? g - 1u : 0u, far = min(g + 1u, HMB_BVH_QUANTUM_MAX);
    if ((near == 0u || boundAt(near, origin, step) <= x) &&
        (far == HMB_BVH_QUANTUM_MAX || boundAt(far + 1u, origin, step) > x)) {
      uint steps = near;
      if (near + 1u <= far && boundAt(near + 1u, origin, step) <= x) steps = near + 1u;
      if (near + 2u <= far && boundAt(near + 2u, origin, step) <= x) steps = near + 2u;
      return steps;
    }
  }
  uint low = 0u, high = HMB_BVH_QUANTUM_MAX;
  while (low < high) {
    const uint middle = (low + high + 1u) >> 1u;
    if (boundAt(middle, origin, step) <= x) low = middle;
    else high = middle - 1u;
  }
  return low;
}

// The fewest steps whose bound is at or above x (HMB_BVH_QUANTUM_MAX when none is), found as
// stepsBelow finds its answer.
uint stepsAbove(float x, float origin, float step) {
  if (step == 0.0) return x <= origin ? 0u : HMB_BVH_QUANTUM_MAX;
  const float guess = ceil((x - origin) / step);
  if (guess >= 0.0 && guess <= float(HMB_BVH_QUANTUM_MAX)) {
    const uint g = uint(guess), near = g > 0u ? g - 1u : 0u, far = min(g + 1u, HMB_BVH_QUANTUM_MAX);
    if ((near == 0u || boundAt(near - 1u, origin, step) < x) &&
        (far == HMB_BVH_QUANTUM_MAX || boundAt(far, origin, step) >= x)) {
      uint steps = far;
      if (far >= near + 1u && boundAt(far - 1u, origin, step) >= x) steps = far - 1u;
      if (far >= near + 2u && boundAt(far - 2u, origin, step) >= x) steps = far - 2u;
      return steps;
    }
  }
  uint low = 0u, high = HMB_BVH_QUANTUM_MAX;
  while (low < high) {
    const uint middle = (low + high) >> 1u;
    if (boundAt(middle, origin, step) >= x) high = middle;
    else low = middle + 1u;
  }
  return low;
}

// One axis's bounds lo..hi as a packed node's word: the steps below, and above in the high half.
uint packBounds(float lo, float hi, float origin, float step) {
  return stepsBelow(lo, origin, step) | (stepsAbove(hi, origin, step) << 16u);
}

// The box lo..hi in the frame's steps (x, y, z of a packed node); an empty box packs as
// lower HMB_BVH_QUANTUM_MAX, upper 0, which unpacks to no box at all.
uvec3 packBox(vec3 lo, vec3 hi, BvhFrame frame) {
  if (!all(lessThanEqual(lo, hi))) return uvec3(HMB_BVH_QUANTUM_MAX);
  return uvec3(packBounds(lo.x, hi.x, frame.origin.x, frame.step.x),
               packBounds(lo.y, hi.y, frame.origin.y, frame.step.y),
               packBounds(lo.z, hi.z, frame.origin.z, frame.step.z));
}

uint packLeftOrFirstCount(uint leftOrFirst, uint count) { return (leftOrFirst << HMB_BVH_PACKED_COUNT_BITS) | count; }
uint packedCount(uvec4 node) { return node.w & HMB_BVH_PACKED_MAX_COUNT; }
uint packedLeftOrFirst(uvec4 node) { return node.w >> HMB_BVH_PACKED_COUNT_BITS; }

vec3 packedLower(uvec4 node, BvhFrame frame) {
  return vec3(boundAt(node.x & 0xffffu, frame.origin.x, frame.step.x),
              boundAt(node.y & 0xffffu, frame.origin.y, frame.step.y),
              boundAt(node.z & 0xffffu, frame.origin.z, frame.step.z));
}
vec3 packedUpper(uvec4 node, BvhFrame frame) {
  return vec3(boundAt(node.x >> 16u, frame.origin.x, frame.step.x), boundAt(node.y >> 16u, frame.origin.y, frame.step.y),
              boundAt(node.z >> 16u, frame.origin.z, frame.step.z));
}

#endif
