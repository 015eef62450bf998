// A kernel that shades surfaces (kernels/shared/shading.glsl), in two builds: with the texture
// path, and without it (no texel reads, no uv interpolation) for scenes whose materials have
// no texture. A kernel that also traces rays (kernels/trace/closest_hit.glsl) has each of those
// with and without the top-level walk, left out for scenes of one instance. The frame plan
// lists both paths as run or skipped; a build is made the first time a frame needs it.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb {
class FramePlan;
class GpuScene;
class TraceScene;
}  // namespace hmb

namespace hmb::passes {

class HitShading;

class ShadingKernel {
 public:
  static constexpr const char* kTexturePath = "texture-path";
  static constexpr const char* kTopLevelWalk = "top-level-walk";
  enum class Rays { None, Traced };
  // rays: whether the kernel traces rays (and so has the top-level walk's constant); hits: how
  // ray hits are shaded, for the kernels that shade them (null: the library's way).
  // kernelConstants: the kernel's own specialization constants, ids from
  // HMB_SPEC_KERNEL_CONSTANTS_FIRST on, the same in every build.
  ShadingKernel(const vk::Context& context, const kernels::KernelFacts& kernel, Rays rays = Rays::None,
                const HitShading* hits = nullptr, std::span<const uint32_t> kernelConstants = {});
  ~ShadingKernel();

  // The build for this scene: without the texture path where scene.texturePath() is false, and
  // for a kernel that traces `traced`, without the top-level walk where scene.topLevelWalk() is
  // false and `traced` has one instance.
  const vk::ComputeKernel& forScene(const GpuScene& scene, const TraceScene* traced = nullptr) const;

 private:
  // The kernel with these specialization constants: the embedded builds, or with a user's
  // shading the builds compiled from it.
  std::unique_ptr<vk::ComputeKernel> build(std::span<const uint32_t> shading) const;

  const vk::Context& context_;
  std::string name_;
  uint32_t pushConstantBytes_;
  bool traces_;              // the kernel traces rays: it has the top-level walk's constant
  const HitShading* hits_;  // non-null with a user's shading: the kernel's builds come from it
  std::vector<uint32_t> kernelConstants_;
  // [texture path][top-level walk]; the full build is made up front.
  mutable std::unique_ptr<vk::ComputeKernel> builds_[2][2];
};

// Lists the texture path of the shading passes the plan runs as run inside them or skipped,
// and why, and the same for the top-level walk of the passes that trace; call it once the plan
// holds every pass.
void planTexturePath(FramePlan& plan, const GpuScene& scene);

}  // namespace hmb::passes
