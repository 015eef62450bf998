// A kernel that shades surfaces (kernels/shared/shading.glsl), in two builds: with the texture
// path, and without it (no texel reads, no uv interpolation) for scenes whose materials have
// no texture. The frame plan lists the path as run or skipped; the second build is made the
// first time a frame leaves the path out.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb {
class FramePlan;
class GpuScene;
}  // namespace hmb

namespace hmb::passes {

class HitShading;

class ShadingKernel {
 public:
  static constexpr const char* kTexturePath = "texture-path";
  // hits: how ray hits are shaded, for the kernels that shade them (null: the library's way).
  ShadingKernel(const vk::Context& context, std::string_view kernelName, uint32_t pushConstantBytes,
                const HitShading* hits = nullptr);
  ~ShadingKernel();

  // The build that shades this scene: without the texture path where scene.texturePath() is false.
  const vk::ComputeKernel& forScene(const GpuScene& scene) const;

 private:
  // The kernel with these specialization constants: the embedded builds, or with a user's
  // shading the builds compiled from it.
  std::unique_ptr<vk::ComputeKernel> build(std::span<const uint32_t> specialization) const;

  const vk::Context& context_;
  std::string name_;
  uint32_t pushConstantBytes_;
  const HitShading* hits_;  // non-null with a user's shading: the kernel's builds come from it
  std::unique_ptr<vk::ComputeKernel> textured_;
  mutable std::unique_ptr<vk::ComputeKernel> untextured_;
};

// Lists the texture path of the shading passes the plan runs as run inside them or skipped,
// and why; call it once the plan holds every pass.
void planTexturePath(FramePlan& plan, const GpuScene& scene);

}  // namespace hmb::passes
