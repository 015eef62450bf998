#version 450
// The ray mask's length -> the indirect dispatch of the passes that run per masked pixel
// (reveal_background, the background layer's gather): HMB_MASK_LIST_GROUP lanes per group,
// folded into rows of at most 65535 groups. An empty mask dispatches no group.
#extension GL_GOOGLE_include_directive : require
#include "hybrid_layout.h"

layout(local_size_x = 1) in;

layout(std430, binding = HMB_SIZE_REVEAL_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };

void main() {
  const uint groups = (counters.maskCount + HMB_MASK_LIST_GROUP - 1u) / HMB_MASK_LIST_GROUP;
  counters.dispatchX = groups == 0u ? 0u : min(groups, 65535u);
  counters.dispatchY = groups == 0u ? 0u : (groups + 65534u) / 65535u;
  counters.dispatchZ = 1u;
}
