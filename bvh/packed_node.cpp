#include "bvh/packed_node.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hmb::bvh {

float boundAt(uint32_t steps, float origin, float step) {
  const float offset = float(steps) * step;
  return origin + offset;
}

gpu::BvhFrame frameOf(const Aabb& root) {
  gpu::BvhFrame frame{glm::vec4(0.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)};
  if (root.empty()) return frame;
  constexpr float kMax = std::numeric_limits<float>::max();
  const glm::vec3 lo = glm::clamp(root.min, glm::vec3(-kMax), glm::vec3(kMax));
  const glm::vec3 hi = glm::clamp(root.max, glm::vec3(-kMax), glm::vec3(kMax));
  const float perStep = 1.0f / float(HMB_BVH_QUANTUM_MAX);
  glm::vec3 step = (hi * perStep - lo * perStep) * (1.0f + 1.0f / 1024.0f);
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 64 && boundAt(HMB_BVH_QUANTUM_MAX, lo[a], step[a]) < hi[a]; ++i)
      step[a] = step[a] * 2.0f + std::numeric_limits<float>::min();
  frame.origin = glm::vec4(lo, 0.0f);
  frame.step = glm::vec4(step, 0.0f);
  return frame;
}

// Both searches start from the three steps around the quotient's guess where the bounds there
// confirm it (kernels/bvh/packed_node.glsl says why), else from the whole range.
uint32_t stepsBelow(float x, float origin, float step) {
  uint32_t low = 0, high = HMB_BVH_QUANTUM_MAX;
  const float guess = (x - origin) / step;
  if (guess >= 0.0f && guess <= float(HMB_BVH_QUANTUM_MAX)) {
    const auto g = static_cast<uint32_t>(guess);
    const uint32_t near = g > 0 ? g - 1 : 0, far = std::min<uint32_t>(g + 1, HMB_BVH_QUANTUM_MAX);
    if ((near == 0 || boundAt(near, origin, step) <= x) &&
        (far == HMB_BVH_QUANTUM_MAX || boundAt(far + 1, origin, step) > x))
      low = near, high = far;
  }
  while (low < high) {
    const uint32_t middle = (low + high + 1) >> 1;
    if (boundAt(middle, origin, step) <= x)
      low = middle;
    else
      high = middle - 1;
  }
  return low;
}

uint32_t stepsAbove(float x, float origin, float step) {
  uint32_t low = 0, high = HMB_BVH_QUANTUM_MAX;
  const float guess = std::ceil((x - origin) / step);
  if (guess >= 0.0f && guess <= float(HMB_BVH_QUANTUM_MAX)) {
    const auto g = static_cast<uint32_t>(guess);
    const uint32_t near = g > 0 ? g - 1 : 0, far = std::min<uint32_t>(g + 1, HMB_BVH_QUANTUM_MAX);
    if ((near == 0 || boundAt(near - 1, origin, step) < x) &&
        (far == HMB_BVH_QUANTUM_MAX || boundAt(far, origin, step) >= x))
      low = near, high = far;
  }
  while (low < high) {
    const uint32_t middle = (low + high) >> 1;
    if (boundAt(middle, origin, step) >= x)
      high = middle;
    else
      low = middle + 1;
  }
  return low;
}

gpu::BvhPackedNode packNode(const Node& node, const gpu::BvhFrame& frame) {
  const Aabb box = boundsOf(node);
  uint32_t words[3];
  for (int a = 0; a < 3; ++a)
    words[a] = box.empty() ? HMB_BVH_QUANTUM_MAX
                           : stepsBelow(box.min[a], frame.origin[a], frame.step[a]) |
                                 (stepsAbove(box.max[a], frame.origin[a], frame.step[a]) << 16);
  return {words[0], words[1], words[2], (node.leftOrFirst << HMB_BVH_PACKED_COUNT_BITS) | node.count};
}

Node unpackNode(const gpu::BvhPackedNode& node, const gpu::BvhFrame& frame) {
  const uint32_t words[3] = {node.x, node.y, node.z};
  Aabb box;
  for (int a = 0; a < 3; ++a) {
    box.min[a] = boundAt(words[a] & 0xffffu, frame.origin[a], frame.step[a]);
    box.max[a] = boundAt(words[a] >> 16, frame.origin[a], frame.step[a]);
  }
  Node out{};
  setBounds(out, box);
  out.leftOrFirst = node.leftOrFirstCount >> HMB_BVH_PACKED_COUNT_BITS;
  out.count = node.leftOrFirstCount & HMB_BVH_PACKED_MAX_COUNT;
  return out;
}

}  // namespace hmb::bvh
