#include "runtime/vulkan/kernel_interface.h"

#include <algorithm>
#include <memory>

#include <spirv_cross/spirv_cross_c.h>

#include "hmblur/error.h"
#include "runtime/vulkan/kernel_registry.h"

namespace hmb::vk {
namespace {

using ContextHandle = std::unique_ptr<spvc_context_s, decltype(&spvc_context_destroy)>;

void require(spvc_result result, spvc_context context, const EmbeddedKernel& kernel) {
  if (result != SPVC_SUCCESS)
    throw Error("cannot read the SPIR-V of kernel '" + std::string(kernel.name) +
                "': " + spvc_context_get_last_error_string(context));
}

std::span<const spvc_reflected_resource> resourcesOf(spvc_resources resources, spvc_resource_type type,
                                                     spvc_context context, const EmbeddedKernel& kernel) {
  const spvc_reflected_resource* list = nullptr;
  size_t count = 0;
  require(spvc_resources_get_resource_list_for_type(resources, type, &list, &count), context, kernel);
  return {list, count};
}

void fitsUnder(std::string& why, const std::string& kernelName, const char* what, uint64_t needed,
               const char* limitName, uint64_t limit) {
  if (why.empty() && needed > limit)
    why = "kernel '" + kernelName + "' needs " + std::to_string(needed) + " " + what + "; the device allows " +
          std::to_string(limit) + " (" + limitName + ")";
}

}  // namespace

KernelInterface reflectKernel(const EmbeddedKernel& kernel) {
  spvc_context raw = nullptr;
  if (spvc_context_create(&raw) != SPVC_SUCCESS) throw Error("cannot create a SPIR-V reflection context");
  const ContextHandle context(raw, &spvc_context_destroy);

  spvc_parsed_ir ir = nullptr;
  require(spvc_context_parse_spirv(raw, kernel.words, kernel.wordCount, &ir), raw, kernel);
  spvc_compiler compiler = nullptr;
  require(spvc_context_create_compiler(raw, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler), raw,
          kernel);
  spvc_resources resources = nullptr;
  require(spvc_compiler_create_shader_resources(compiler, &resources), raw, kernel);

  KernelInterface result;
  auto setOf = [&](const spvc_reflected_resource& r) {
    const unsigned set = spvc_compiler_get_decoration(compiler, r.id, SpvDecorationDescriptorSet);
    result.highestDescriptorSet = std::max(result.highestDescriptorSet, set);
    return set;
  };
  for (const spvc_reflected_resource& r : resourcesOf(resources, SPVC_RESOURCE_TYPE_STORAGE_BUFFER, raw, kernel))
    if (setOf(r) == 0)
      result.storageBufferBindings.push_back(spvc_compiler_get_decoration(compiler, r.id, SpvDecorationBinding));
  std::sort(result.storageBufferBindings.begin(), result.storageBufferBindings.end());
  for (const spvc_reflected_resource& r : resourcesOf(resources, SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, raw, kernel)) {
    setOf(r);
    ++result.uniformBuffers;
  }
  // A buffer texture (textureBuffer, read with texelFetch) is a uniform texel buffer, a 2D
  // texture read without a sampler a sampled image; any other image is not a descriptor this
  // project binds.
  for (const spvc_reflected_resource& r : resourcesOf(resources, SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, raw, kernel)) {
    const spvc_type type = spvc_compiler_get_type_handle(compiler, r.type_id);
    const bool inSetZero = setOf(r) == 0, storage = spvc_type_get_image_is_storage(type);
    const SpvDim dimension = spvc_type_get_image_dimension(type);
    const uint32_t binding = spvc_compiler_get_decoration(compiler, r.id, SpvDecorationBinding);
    if (inSetZero && dimension == SpvDimBuffer && !storage)
      result.texelBufferBindings.push_back(binding);
    else if (inSetZero && dimension == SpvDim2D && !storage && !spvc_type_get_image_arrayed(type))
      result.sampledImageBindings.push_back(binding);
    else
      ++result.otherDescriptors;
  }
  for (const spvc_reflected_resource& r : resourcesOf(resources, SPVC_RESOURCE_TYPE_STORAGE_IMAGE, raw, kernel)) {
    const spvc_type type = spvc_compiler_get_type_handle(compiler, r.type_id);
    if (setOf(r) == 0 && spvc_type_get_image_dimension(type) == SpvDim2D && !spvc_type_get_image_arrayed(type))
      result.storageImageBindings.push_back(spvc_compiler_get_decoration(compiler, r.id, SpvDecorationBinding));
    else
      ++result.otherDescriptors;
  }
  for (std::vector<uint32_t>* list :
       {&result.texelBufferBindings, &result.sampledImageBindings, &result.storageImageBindings})
    std::sort(list->begin(), list->end());
  for (spvc_resource_type type : {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS,
                                  SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE})
    result.otherDescriptors += uint32_t(resourcesOf(resources, type, raw, kernel).size());

  for (const spvc_reflected_resource& r : resourcesOf(resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT, raw, kernel)) {
    size_t bytes = 0;
    require(spvc_compiler_get_declared_struct_size(compiler, spvc_compiler_get_type_handle(compiler, r.base_type_id),
                                                   &bytes),
            raw, kernel);
    result.pushConstantBytes = std::max(result.pushConstantBytes, uint32_t(bytes));
  }
  const SpvCapability* capabilities = nullptr;
  size_t capabilityCount = 0;
  require(spvc_compiler_get_declared_capabilities(compiler, &capabilities, &capabilityCount), raw, kernel);
  for (size_t i = 0; i < capabilityCount; ++i)
    result.usesDeviceAddresses |= capabilities[i] == SpvCapabilityPhysicalStorageBufferAddresses;
  for (unsigned axis = 0; axis < 3; ++axis)
    result.localSize[axis] =
        std::max(1u, spvc_compiler_get_execution_mode_argument_by_index(compiler, SpvExecutionModeLocalSize, axis));
  return result;
}

std::string whyKernelDoesNotFit(const std::string& kernelName, const KernelInterface& kernel,
                                const VkPhysicalDeviceLimits& limits) {
  std::string why;
  const auto storageBuffers = uint64_t(kernel.storageBufferBindings.size());
  fitsUnder(why, kernelName, "storage buffers in one stage", storageBuffers, "maxPerStageDescriptorStorageBuffers",
            limits.maxPerStageDescriptorStorageBuffers);
  fitsUnder(why, kernelName, "storage buffers in one set", storageBuffers, "maxDescriptorSetStorageBuffers",
            limits.maxDescriptorSetStorageBuffers);
  // Uniform texel buffers count against the sampled-image limits.
  const auto sampled = uint64_t(kernel.texelBufferBindings.size() + kernel.sampledImageBindings.size());
  fitsUnder(why, kernelName, "texel buffers and sampled images in one stage", sampled,
            "maxPerStageDescriptorSampledImages", limits.maxPerStageDescriptorSampledImages);
  fitsUnder(why, kernelName, "texel buffers and sampled images in one set", sampled, "maxDescriptorSetSampledImages",
            limits.maxDescriptorSetSampledImages);
  const auto storageImages = uint64_t(kernel.storageImageBindings.size());
  fitsUnder(why, kernelName, "storage images in one stage", storageImages, "maxPerStageDescriptorStorageImages",
            limits.maxPerStageDescriptorStorageImages);
  fitsUnder(why, kernelName, "bytes of push constants", kernel.pushConstantBytes, "maxPushConstantsSize",
            limits.maxPushConstantsSize);
  const char* axes[] = {"maxComputeWorkGroupSize[0]", "maxComputeWorkGroupSize[1]", "maxComputeWorkGroupSize[2]"};
  for (int axis = 0; axis < 3; ++axis)
    fitsUnder(why, kernelName, "invocations along a workgroup axis", kernel.localSize[axis], axes[axis],
              limits.maxComputeWorkGroupSize[axis]);
  fitsUnder(why, kernelName, "invocations per workgroup",
            uint64_t(kernel.localSize[0]) * kernel.localSize[1] * kernel.localSize[2],
            "maxComputeWorkGroupInvocations", limits.maxComputeWorkGroupInvocations);
  return why;
}

}  // namespace hmb::vk
