// Where an invocation is in a long 1D run of groups folded into rows (shared/dispatch.h).
#ifndef HMB_KERNELS_SHARED_INDEXING_GLSL
#define HMB_KERNELS_SHARED_INDEXING_GLSL

// The group size is passed in, not read from gl_WorkGroupSize: glslang resolves that constant
// where it is used, and in a header included before the kernel's local_size declaration it
// is silently (1, 1, 1).
// The group's index in the run.
uint foldedGroupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// The invocation's index in the run, for groups of groupSize invocations (of any shape).
uint linearInvocationIndex(uint groupSize) { return foldedGroupIndex() * groupSize + gl_LocalInvocationIndex; }

#endif
