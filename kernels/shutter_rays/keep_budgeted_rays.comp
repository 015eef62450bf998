#version 450
// Per entry of list_shutter_rays' list, under a ray budget: kept when its priority bucket lies
// above select_ray_budget's threshold, or in it below the range of pixel indices where the
// allowance ran out; the kept entries form a list of their own, with its dispatch, for
// trace_shutter_rays. The others keep the blur's colour.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "shutter_rays_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_MASK_LIST_GROUP) in;

layout(std430, binding = HMB_RAY_BUDGET_KEEP_BINDING_LIST) readonly buffer List { uint list[]; };
layout(std430, binding = HMB_RAY_BUDGET_KEEP_BINDING_PRIORITIES) readonly buffer Priorities { uint priorities[]; };
layout(std430, binding = HMB_RAY_BUDGET_KEEP_BINDING_COUNTERS) readonly buffer Counters { ShutterRayCounters counters; };
layout(std430, binding = HMB_RAY_BUDGET_KEEP_BINDING_BUDGET) readonly buffer Budget { ShutterRayBudget budget; };
layout(std430, binding = HMB_RAY_BUDGET_KEEP_BINDING_KEPT) writeonly buffer Kept { uint kept[]; };
layout(std430, binding = HMB_RAY_BUDGET_KEEP_BINDING_KEPT_COUNTERS) buffer KeptCounters {
  ShutterRayCounters keptCounters;
};

void main() {
  const uint entry = linearInvocationIndex(HMB_MASK_LIST_GROUP);
  if (entry >= counters.count) return;
  const uint listed = list[entry];
  const uint priority = priorities[entry];
  if (priority < budget.threshold) return;
  if (priority == budget.threshold &&
      rayBudgetTieRange(shutterRayEntryPixel(listed), budget.rangePixels) >= budget.tieRange)
    return;
  const uint slot = atomicAdd(keptCounters.count, 1u);
  kept[slot] = listed;
  if (slot % HMB_MASK_LIST_GROUP != 0u) return;
  const uint group = slot / HMB_MASK_LIST_GROUP;
  atomicMax(keptCounters.dispatchX, min(group + 1u, HMB_SHUTTER_RAY_GROUPS_PER_ROW));
  atomicMax(keptCounters.dispatchY, group / HMB_SHUTTER_RAY_GROUPS_PER_ROW + 1u);
  if (group == 0u) keptCounters.dispatchZ = 1u;
}
