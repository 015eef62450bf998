// Dispatch sizes that fit every device: Vulkan guarantees only 65535 workgroups per axis, so a
// long 1D run of groups folds into rows of 65535. Kernels that size their own indirect
// dispatches and the host (vk::FrameRecorder) fold alike; kernels read the group's place in
// the run with foldedGroupIndex() (shared/indexing.glsl).
#ifndef HMB_KERNELS_SHARED_DISPATCH_H
#define HMB_KERNELS_SHARED_DISPATCH_H

#include "glsl_cpp.h"

// Loop rounds an invocation may take where the driver has a budget: 7/8 of the 65535 llvmpipe
// 22.3 allows (it ends every loop of an invocation past them, silently), an eighth kept for
// what a kernel's count of its rounds misses (vk::DeviceProfile::loopBudget).
#define HMB_LOOP_BUDGET 57344u

HMB_GPU_BEGIN

// The group counts vkCmdDispatchIndirect reads (VkDispatchIndirectCommand), where a kernel
// sizes another's dispatch.
struct IndirectDispatch {
  uint x;
  uint y;
  uint z;
};

HMB_SHARED uvec3 foldedGroups(uint groups) {
  return groups == 0u ? uvec3(0u, 0u, 1u) : uvec3(min(groups, 65535u), (groups + 65534u) / 65535u, 1u);
}

HMB_GPU_END

HMB_CHECK_SIZE(IndirectDispatch, 12)

#endif
