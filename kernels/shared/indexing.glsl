// Linear invocation index of a 1D kernel dispatched as a 2D grid of groups (a dispatch has at
// most 65535 groups per axis on many devices, so long arrays fold into rows of groups; the
// host folds with vk::foldedGroups).
#ifndef HMB_KERNELS_SHARED_INDEXING_GLSL
#define HMB_KERNELS_SHARED_INDEXING_GLSL

// The group size is passed in, not read from gl_WorkGroupSize: glslang resolves that constant
// where it is used, and in a header included before the kernel's local_size declaration it
// is silently (1, 1, 1).
uint linearInvocationIndex(uint groupSize) {
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  return group * groupSize + gl_LocalInvocationID.x;
}

#endif
