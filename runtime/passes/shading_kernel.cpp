#include "runtime/passes/shading_kernel.h"

#include <initializer_list>
#include <string>

#include "hmblur/frame_plan.h"
#include "hmblur/hit_shading.h"
#include "kernels/manifest.h"
#include "kernels/shared/scene_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/reference_stage.h"
#include "runtime/passes/resolve_gbuffer_pass.h"
#include "runtime/passes/reveal_pass.h"
#include "runtime/passes/shutter_rays_pass.h"

namespace hmb::passes {

namespace {

const HitShading* customOnly(const HitShading* hits) { return hits && hits->custom() ? hits : nullptr; }

}  // namespace

ShadingKernel::ShadingKernel(const vk::Context& context, const kernels::KernelFacts& kernel, Rays rays,
                             const HitShading* hits, std::span<const uint32_t> kernelConstants)
    : context_(context),
      name_(kernel.name),
      pushConstantBytes_(kernel.pushBytes),
      traces_(rays == Rays::Traced),
      hits_(customOnly(hits)),
      kernelConstants_(kernelConstants.begin(), kernelConstants.end()) {
  const uint32_t full[2] = {1u, 1u};  // texture path, top-level walk
  builds_[1][1] = build(kernelConstants_.empty() ? std::span<const uint32_t>{} : std::span(full));
}

ShadingKernel::~ShadingKernel() = default;

std::unique_ptr<vk::ComputeKernel> ShadingKernel::build(std::span<const uint32_t> shading) const {
  // The shading's constants, then the kernel's own from their first id on (a kernel without the
  // top-level walk's constant ignores its entry).
  static_assert(HMB_SPEC_KERNEL_CONSTANTS_FIRST == 2);
  std::vector<uint32_t> specialization(shading.begin(), shading.end());
  if (!kernelConstants_.empty()) {
    specialization.resize(HMB_SPEC_KERNEL_CONSTANTS_FIRST, 1u);
    specialization.insert(specialization.end(), kernelConstants_.begin(), kernelConstants_.end());
  }
  if (hits_)
    return std::make_unique<vk::ComputeKernel>(context_, name_, hits_->buildsFor(name_), pushConstantBytes_,
                                               specialization);
  return std::make_unique<vk::ComputeKernel>(context_, name_, pushConstantBytes_, specialization);
}

const vk::ComputeKernel& ShadingKernel::forScene(const GpuScene& scene, const TraceScene* traced) const {
  const bool texture = scene.texturePath();
  const bool topLevel = !traces_ || scene.topLevelWalk() || !traced || traced->instanceCount() != 1;
  std::unique_ptr<vk::ComputeKernel>& kernel = builds_[texture ? 1 : 0][topLevel ? 1 : 0];
  if (!kernel) {
    static_assert(HMB_SPEC_TEXTURE_PATH == 0 && HMB_SPEC_TRACE_TOP_LEVEL == 1);
    const uint32_t specialization[2] = {texture ? 1u : 0u, topLevel ? 1u : 0u};  // VkBool32s
    kernel = build(std::span(specialization, traces_ ? 2 : 1));
  }
  return *kernel;
}

namespace {

// Lists a code path inside those of `passes` the plan runs: as run within them, or as skipped
// with "`why`: <those passes> <skipped>"; nothing when the plan runs none of them.
void planCodePath(FramePlan& plan, const char* path, std::initializer_list<const char*> passes, bool runs,
                  const std::string& why, const std::string& skipped) {
  std::string inside;
  for (const char* name : passes)
    if (plan.runs(name)) inside += (inside.empty() ? "" : ", ") + std::string(name);
  if (inside.empty()) return;
  if (runs)
    plan.runWithin(path, inside);
  else
    plan.skip(path, why + ": " + inside + " " + skipped);
}

}  // namespace

void planTexturePath(FramePlan& plan, const GpuScene& scene) {
  planCodePath(plan, ShadingKernel::kTexturePath,
               {ResolveGBufferPass::kName, RevealPass::kName, ShutterRaysPass::kTrace, ReferenceStage::kAccumulate},
               scene.texturePath(),
               "no material has a texture", "run without texel reads and uv interpolation");
  planCodePath(plan, ShadingKernel::kTopLevelWalk, {RevealPass::kName, ShutterRaysPass::kTrace, ReferenceStage::kAccumulate},
               scene.topLevelWalk(), "the scene has one instance", "enter its tree with no top level over it");
}

}  // namespace hmb::passes
