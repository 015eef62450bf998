#version 450
// Per entry of list_shutter_rays' list, under a ray budget: the pairs of rays of the threshold
// bucket's pixels (select_ray_budget's), counted per range of pixel indices, for
// select_ray_budget to split the bucket's ties by pixel index.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "shutter_rays_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_MASK_LIST_GROUP) in;

layout(std430, binding = HMB_RAY_BUDGET_TALLY_BINDING_LIST) readonly buffer List { uint list[]; };
layout(std430, binding = HMB_RAY_BUDGET_TALLY_BINDING_PRIORITIES) readonly buffer Priorities { uint priorities[]; };
layout(std430, binding = HMB_RAY_BUDGET_TALLY_BINDING_COUNTERS) readonly buffer Counters { ShutterRayCounters counters; };
layout(std430, binding = HMB_RAY_BUDGET_TALLY_BINDING_BUDGET) buffer Budget { ShutterRayBudget budget; };

void main() {
  const uint entry = linearInvocationIndex(HMB_MASK_LIST_GROUP);
  if (entry >= counters.count || priorities[entry] != budget.threshold) return;
  const uint listed = list[entry];
  atomicAdd(budget.ties[rayBudgetTieRange(shutterRayEntryPixel(listed), budget.rangePixels)],
            shutterRayEntryRays(listed) / 2u);
}
