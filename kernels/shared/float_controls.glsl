// Every kernel keeps NaN, infinity and the sign of zero as IEEE 754 has them (the SPIR-V
// execution mode SignedZeroInfNanPreserve for 32-bit floats). Without it Vulkan lets a driver
// assume that no float is NaN or infinite ("Precision and Operation of SPIR-V Instructions"),
// and fold away the isnan/isinf tests and NaN-aware comparisons that keep bad input (NaN
// depths, infinite velocities, overflowing coordinates) out of the images. The context
// requires shaderSignedZeroInfNanPreserveFloat32 (runtime/vulkan/context.cpp). Each kernel
// includes this file first; KernelFloatControlsTest (tests/runtime/kernel_pipelines_test.cpp)
// checks that every embedded build declares the mode, HitShadingBuildsTest the builds compiled
// with a user's shading.
#ifndef HMB_FLOAT_CONTROLS_GLSL
#define HMB_FLOAT_CONTROLS_GLSL
#extension GL_EXT_spirv_intrinsics : require
spirv_execution_mode(extensions = ["SPV_KHR_float_controls"], capabilities = [4466], 4461, 32);
#endif
