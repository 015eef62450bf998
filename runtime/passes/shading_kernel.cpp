#include "runtime/passes/shading_kernel.h"

#include <array>

#include "kernels/shared/scene_layout.h"
#include "runtime/frame_plan.h"
#include "runtime/gpu_scene.h"
#include "runtime/passes/hit_shading.h"
#include "runtime/passes/reference_stage.h"
#include "runtime/passes/resolve_gbuffer_pass.h"
#include "runtime/passes/reveal_pass.h"

namespace hmb::passes {

namespace {

const HitShading* customOnly(const HitShading* hits) { return hits && hits->custom() ? hits : nullptr; }

}  // namespace

ShadingKernel::ShadingKernel(const vk::Context& context, std::string_view kernelName,
                             uint32_t pushConstantBytes, const HitShading* hits)
    : context_(context),
      name_(kernelName),
      pushConstantBytes_(pushConstantBytes),
      hits_(customOnly(hits)),
      textured_(build({})) {}

ShadingKernel::~ShadingKernel() = default;

std::unique_ptr<vk::ComputeKernel> ShadingKernel::build(std::span<const uint32_t> specialization) const {
  if (hits_)
    return std::make_unique<vk::ComputeKernel>(context_, name_, hits_->buildsFor(name_), pushConstantBytes_,
                                               specialization);
  return std::make_unique<vk::ComputeKernel>(context_, name_, pushConstantBytes_, specialization);
}

const vk::ComputeKernel& ShadingKernel::forScene(const GpuScene& scene) const {
  if (scene.texturePath()) return *textured_;
  if (!untextured_) {
    std::array<uint32_t, HMB_SPEC_TEXTURE_PATH + 1> specialization{};
    specialization[HMB_SPEC_TEXTURE_PATH] = 0u;  // VkBool32 false
    untextured_ = build(specialization);
  }
  return *untextured_;
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
}

}  // namespace hmb::passes
