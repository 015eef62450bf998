#version 450
// After build_level ran level L: sizes level L + 1's dispatch from the tasks L appended, and
// empties the count that level L + 2 will append to; sizes build_small_tasks' dispatch from
// the small tasks so far.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "bvh_build_common.glsl"
#include "../shared/dispatch.h"

layout(local_size_x = 1) in;

void main() {
  const uint parity = params.level & 1u;
  const uint next = counters.taskCount[1u - parity];
  counters.dispatch[1u - parity] = uvec4(foldedGroups(next), 0u);
  counters.taskCount[parity] = 0u;
  counters.dispatch[parity] = uvec4(0u, 0u, 1u, 0u);
  counters.smallDispatch =
      uvec4(foldedGroups((counters.smallTaskCount + HMB_BVH_SMALL_TASK_GROUP - 1u) / HMB_BVH_SMALL_TASK_GROUP), 0u);
}
