// Linear invocation index of a 1D kernel dispatched as a 2D grid of groups (a dispatch has at
// most 65535 groups per axis on many devices, so long arrays fold into rows of groups).
#ifndef HMB_KERNELS_SHARED_INDEXING_GLSL
#define HMB_KERNELS_SHARED_INDEXING_GLSL

uint linearInvocationIndex() {
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  return group * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
}

#endif
