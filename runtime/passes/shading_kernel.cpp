#include "runtime/passes/shading_kernel.h"

#include <array>

#include "kernels/shared/scene_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/frame_plan.h"
#include "runtime/gpu_scene.h"
#include "runtime/passes/hit_shading.h"
#include "runtime/passes/reference_stage.h"
#include "runtime/passes/resolve_gbuffer_pass.h"
#include "runtime/passes/reveal_pass.h"
#include "runtime/trace_scene.h"

namespace hmb::passes {

namespace {

const HitShading* customOnly(const HitShading* hits) { return hits && hits->custom() ? hits : nullptr; }

}  // namespace

ShadingKernel::ShadingKernel(const vk::Context& context, std::string_view kernelName,
                             uint32_t pushConstantBytes, Rays rays, const HitShading* hits)
    : context_(context),
      name_(kernelName),
      pushConstantBytes_(pushConstantBytes),
      traces_(rays == Rays::Traced),
      hits_(customOnly(hits)) {
  builds_[1][1] = build({});
}

ShadingKernel::~ShadingKernel() = default;

std::unique_ptr<vk::ComputeKernel> ShadingKernel::build(std::span<const uint32_t> specialization) const {
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

void planTexturePath(FramePlan& plan, const GpuScene& scene) {
  std::string shadingPasses;
  for (const char* name : {ResolveGBufferPass::kName, RevealPass::kName, ReferenceStage::kAccumulate})
    if (plan.runs(name)) shadingPasses += (shadingPasses.empty() ? "" : ", ") + std::string(name);
  if (shadingPasses.empty()) return;
  if (scene.texturePath())
    plan.runWithin(ShadingKernel::kTexturePath, shadingPasses);
  else
    plan.skip(ShadingKernel::kTexturePath,
              "no material has a texture: " + shadingPasses + " run without texel reads and uv interpolation");

  std::string tracingPasses;
  for (const char* name : {RevealPass::kName, ReferenceStage::kAccumulate})
    if (plan.runs(name)) tracingPasses += (tracingPasses.empty() ? "" : ", ") + std::string(name);
  if (tracingPasses.empty()) return;
  if (scene.topLevelWalk())
    plan.runWithin(ShadingKernel::kTopLevelWalk, tracingPasses);
  else
    plan.skip(ShadingKernel::kTopLevelWalk,
              "the scene has one instance: " + tracingPasses + " enter its tree with no top level over it");
}

}  // namespace hmb::passes
