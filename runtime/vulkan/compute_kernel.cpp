#include "runtime/vulkan/compute_kernel.h"

#include <algorithm>
#include <vector>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/check.h"
#include "runtime/vulkan/kernel_interface.h"
#include "runtime/vulkan/kernel_registry.h"
#include "runtime/vulkan/kernel_store.h"
#include "runtime/vulkan/pipeline_cache.h"

namespace hmb::vk {
namespace {

VkDescriptorType descriptorTypeIn(const KernelPipeline& pipeline, uint32_t index) {
  const auto in = [&](const std::vector<uint32_t>& list) { return std::binary_search(list.begin(), list.end(), index); };
  if (in(pipeline.texelBindings)) return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  if (in(pipeline.sampledImageBindings)) return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
  if (in(pipeline.storageImageBindings)) return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

}  // namespace

ComputeKernel::ComputeKernel(const Context& context, const kernels::KernelFacts& kernel,
                             std::span<const uint32_t> specialization)
    : ComputeKernel(context, kernel.name, kernel.pushBytes, specialization) {}

ComputeKernel::ComputeKernel(const Context& context, std::string_view kernelName, uint32_t pushConstantBytes,
                             std::span<const uint32_t> specialization)
    : context_(context), name_(kernelName), pushConstantBytes_(pushConstantBytes) {
  // The key: the name, the push-constant size and the specialization values.
  std::string key = name_;
  key.append(1, '/').append(std::to_string(pushConstantBytes));
  for (const uint32_t value : specialization) key.append(1, '/').append(std::to_string(value));
  pipeline_ = context.kernelStore().find(key, [&] {
    return build(findKernel(kernelName), findKernelIfBuilt(name_ + std::string(kByAddressSuffix)), specialization);
  });
}

ComputeKernel::ComputeKernel(const Context& context, std::string_view kernelName, const KernelBuilds& builds,
                             uint32_t pushConstantBytes, std::span<const uint32_t> specialization)
    : context_(context), name_(kernelName), pushConstantBytes_(pushConstantBytes) {
  if (builds.plain.empty()) throw Error("kernel '" + name_ + "' was given no SPIR-V");
  const EmbeddedKernel plain{name_, builds.plain.data(), builds.plain.size()};
  const EmbeddedKernel byAddress{name_, builds.byAddress.data(), builds.byAddress.size()};
  pipeline_ = build(plain, builds.byAddress.empty() ? nullptr : &byAddress, specialization);  // its own
}

std::shared_ptr<const KernelPipeline> ComputeKernel::build(const EmbeddedKernel& plain,
                                                           const EmbeddedKernel* byAddress,
                                                           std::span<const uint32_t> specialization) const {
  const Context& context = context_;
  const uint32_t pushConstantBytes = pushConstantBytes_;
  auto made = std::make_shared<KernelPipeline>(context.device());
  // The SPIR-V is the truth about what the kernel binds; the device must have room for it
  // before any Vulkan object is made.
  const EmbeddedKernel* spirvBuild = &plain;
  KernelInterface declared = reflectKernel(*spirvBuild);
  std::string doesNotFit = whyKernelDoesNotFit(name_, declared, context.limits());
  // The address build, where there is one, is for devices whose storage-buffer bindings the
  // plain build exceeds (or for every device, when asked).
  const auto& limits = context.limits();
  const uint64_t storageBuffers = declared.storageBufferBindings.size();
  const bool tooManyBuffers = storageBuffers > limits.maxPerStageDescriptorStorageBuffers ||
                              storageBuffers > limits.maxDescriptorSetStorageBuffers;
  if (byAddress && (context.options().bindByAddress || tooManyBuffers)) {
    if (!context.info().bufferDeviceAddress)
      throw Error(doesNotFit.empty() ? "kernel '" + name_ + "': binding by address needs bufferDeviceAddress"
                                     : doesNotFit + ", and lacks bufferDeviceAddress to bind its buffers by address");
    spirvBuild = byAddress;
    declared = reflectKernel(*byAddress);
    doesNotFit = whyKernelDoesNotFit(name_ + " (by address)", declared, context.limits());
    made->bindsByAddress = true;
  }
  if (!doesNotFit.empty()) throw Error(doesNotFit);
  if (declared.usesDeviceAddresses && !context.info().bufferDeviceAddress)
    throw Error("kernel '" + name_ + "' reads buffers by device address, which the device lacks (bufferDeviceAddress)");
  const EmbeddedKernel& spirv = *spirvBuild;
  std::vector<uint32_t>& declaredBindings = made->bindings;
  declaredBindings = declared.storageBufferBindings;
  made->texelBindings = declared.texelBufferBindings;
  made->sampledImageBindings = declared.sampledImageBindings;
  made->storageImageBindings = declared.storageImageBindings;
  for (const std::vector<uint32_t>* list :
       {&made->texelBindings, &made->sampledImageBindings, &made->storageImageBindings})
    declaredBindings.insert(declaredBindings.end(), list->begin(), list->end());
  std::sort(declaredBindings.begin(), declaredBindings.end());
  if (declared.uniformBuffers != 0 || declared.otherDescriptors != 0 || declared.highestDescriptorSet != 0)
    throw Error("kernel '" + name_ + "' declares descriptors other than storage and uniform texel buffers and 2D "
                "images in set 0");
  if (declared.pushConstantBytes > pushConstantBytes)
    throw Error("kernel '" + name_ + "' declares " + std::to_string(declared.pushConstantBytes) +
                " bytes of push constants but its host passes " + std::to_string(pushConstantBytes));
  if (pushConstantBytes > context.limits().maxPushConstantsSize)
    throw Error("kernel '" + name_ + "' needs " + std::to_string(pushConstantBytes) +
                " bytes of push constants; the device allows " +
                std::to_string(context.limits().maxPushConstantsSize) + " (maxPushConstantsSize)");
  const VkDevice device = context.device();
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    std::vector<VkDescriptorSetLayoutBinding> bindings(declaredBindings.size());
    for (size_t i = 0; i < declaredBindings.size(); ++i) {
      bindings[i].binding = declaredBindings[i];
      bindings[i].descriptorType = descriptorTypeIn(*made, declaredBindings[i]);
      bindings[i].descriptorCount = 1;
      bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = uint32_t(bindings.size());
    setInfo.pBindings = bindings.data();
    HMB_VK_CHECK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &made->setLayout));

    const VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &made->setLayout;
    layoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
    layoutInfo.pPushConstantRanges = &pushRange;
    HMB_VK_CHECK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &made->layout));

    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.wordCount * sizeof(uint32_t);
    moduleInfo.pCode = spirv.words;
    HMB_VK_CHECK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));

    std::vector<VkSpecializationMapEntry> entries(specialization.size());
    for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, i * uint32_t(sizeof(uint32_t)), sizeof(uint32_t)};
    const VkSpecializationInfo specializationInfo{uint32_t(entries.size()), entries.data(), specialization.size_bytes(),
                                                  specialization.data()};

    VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipelineInfo.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipelineInfo.stage.module = module;
    pipelineInfo.stage.pName = "main";
    pipelineInfo.stage.pSpecializationInfo = specialization.empty() ? nullptr : &specializationInfo;
    pipelineInfo.layout = made->layout;
    HMB_VK_CHECK(vkCreateComputePipelines(device, context.pipelineCache().handle(), 1, &pipelineInfo, nullptr, &made->pipeline));
    vkDestroyShaderModule(device, module, nullptr);
  } catch (...) {
    if (module) vkDestroyShaderModule(device, module, nullptr);
    throw;  // `made` releases what was made
  }
  return made;
}

ComputeKernel::~ComputeKernel() = default;

uint32_t ComputeKernel::storageBufferCount() const {
  return uint32_t(pipeline_->bindings.size() - pipeline_->texelBindings.size() -
                  pipeline_->sampledImageBindings.size() - pipeline_->storageImageBindings.size());
}
const std::vector<uint32_t>& ComputeKernel::bindings() const { return pipeline_->bindings; }
const std::vector<uint32_t>& ComputeKernel::texelBindings() const { return pipeline_->texelBindings; }
bool ComputeKernel::bindsByAddress() const { return pipeline_->bindsByAddress; }
VkPipeline ComputeKernel::pipeline() const { return pipeline_->pipeline; }
VkPipelineLayout ComputeKernel::layout() const { return pipeline_->layout; }
VkDescriptorSetLayout ComputeKernel::setLayout() const { return pipeline_->setLayout; }

bool ComputeKernel::isTexelBinding(uint32_t index) const {
  return std::binary_search(pipeline_->texelBindings.begin(), pipeline_->texelBindings.end(), index);
}

VkDescriptorType ComputeKernel::descriptorType(uint32_t index) const { return descriptorTypeIn(*pipeline_, index); }

}  // namespace hmb::vk
