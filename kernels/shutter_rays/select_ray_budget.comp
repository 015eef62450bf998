#version 450
// Where a frame's ray budget runs out, in one of two histograms of pairs of rays. First over
// the priority buckets (list_shutter_rays counted them), from the highest down, until the next
// bucket would pass the budget: the pixels of the buckets above it are kept whole, this one's
// (the threshold bucket) share what is left (the allowance). Then over that bucket's pairs per
// range of pixel indices (tally_budget_ties counted them), from the lowest up, to the first
// range the allowance no longer holds: the ranges below it are kept, so the same pixels win the
// ties every run, whatever order the device listed them in. A budget every listed pixel fits
// in keeps them all.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "shutter_rays_layout.h"

layout(local_size_x = 1) in;

layout(std430, binding = HMB_RAY_BUDGET_SELECT_BINDING_BUDGET) buffer Budget { ShutterRayBudget budget; };
layout(push_constant) uniform Params { RayBudgetSelectParams params; };

void main() {
  uint spent = 0u;  // pairs of the buckets (ranges) before the one looked at
  if (params.ties == 0u) {
    budget.threshold = 0u;
    budget.allowance = 0xFFFFFFFFu;
    for (uint b = HMB_RAY_BUDGET_BUCKETS; b-- > 0u;) {
      const uint pairs = budget.histogram[b];
      if (pairs > budget.budgetPairs - spent) {
        budget.threshold = b;
        budget.allowance = budget.budgetPairs - spent;
        return;
      }
      spent += pairs;
    }
    return;
  }
  budget.tieRange = HMB_RAY_BUDGET_BUCKETS;
  for (uint r = 0u; r < HMB_RAY_BUDGET_BUCKETS; ++r) {
    const uint pairs = budget.ties[r];
    if (pairs > budget.allowance - spent) {
      budget.tieRange = r;
      return;
    }
    spent += pairs;
  }
}
