// Every embedded kernel builds a compute pipeline against the layout its shared header
// declares; the validation layer checks the SPIR-V's bindings and push constants against it.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "hmblur/buffer.h"
#include "kernels/manifest.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"
#include "runtime/vulkan/kernel_interface.h"
#include "runtime/vulkan/kernel_registry.h"
#include "runtime/vulkan/kernel_store.h"
#include "runtime/vulkan/kernel_variants.h"
#include "tests/support/expect_error.h"
#include "tests/support/spirv_modes.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using KernelPipelinesTest = VulkanTest;

bool isAddressBuild(std::string_view name) { return name.ends_with(vk::kByAddressSuffix); }

// The manifest's entry of an embedded kernel (its address build's: its plain build's).
const kernels::KernelFacts& layoutOf(std::string_view name) {
  if (isAddressBuild(name)) name.remove_suffix(vk::kByAddressSuffix.size());
  if (const kernels::KernelFacts* facts = kernels::findKernelFacts(name)) return *facts;
  throw std::runtime_error("kernel " + std::string(name) + " is not in kernels/manifest.h");
}

// The manifest and the embedded kernels are the same list: every entry is built, with an address
// build exactly where the entry says so.
TEST(KernelManifestTest, ListsEveryEmbeddedKernelAndItsAddressBuild) {
  size_t plainBuilds = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    const kernels::KernelFacts& facts = layoutOf(kernel.name);
    if (isAddressBuild(kernel.name))
      EXPECT_TRUE(facts.has(kernels::kAddressBuild)) << kernel.name << ": an address build the manifest leaves out";
    else
      ++plainBuilds;
  }
  EXPECT_EQ(plainBuilds, std::size(kernels::kManifest));
  for (const kernels::KernelFacts& facts : kernels::kManifest) {
    EXPECT_NE(vk::findKernelIfBuilt(facts.name), nullptr) << facts.name << " is listed but not built";
    const std::string addressBuild = std::string(facts.name) + std::string(vk::kByAddressSuffix);
    EXPECT_EQ(vk::findKernelIfBuilt(addressBuild) != nullptr, facts.has(kernels::kAddressBuild)) << facts.name;
    EXPECT_LE(facts.texelBindings, facts.bindings) << facts.name;
  }
  EXPECT_EQ(kernels::findKernelFacts("mblur/no_such_kernel"), nullptr);
  static_assert(kernels::kernel("mblur/tile_max").pushBytes == sizeof(gpu::TileMaxParams));
}

TEST_F(KernelPipelinesTest, EveryKernelHasADeclaredLayoutAndBuilds) {
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    if (isAddressBuild(kernel.name)) continue;  // ComputeKernel picks it; see below
    const kernels::KernelFacts& layout = layoutOf(kernel.name);
    if (layout.has(kernels::kInt64Atomics) && !context().info().int64BufferAtomics) continue;
    const vk::ComputeKernel built(context(), kernel.name, layout.pushBytes);
    const bool fits = layout.storageBindings() <= context().limits().maxPerStageDescriptorStorageBuffers &&
                      layout.storageBindings() <= context().limits().maxDescriptorSetStorageBuffers;
    EXPECT_EQ(built.bindsByAddress(), !fits) << kernel.name;
    if (fits) {
      EXPECT_EQ(built.storageBufferCount(), layout.storageBindings()) << kernel.name;
      EXPECT_EQ(built.texelBindings().size(), layout.texelBindings) << kernel.name;
      EXPECT_EQ(built.bindings().size(), layout.bindings) << kernel.name;
    }
    if (layout.has(kernels::kShades)) {
      uint32_t untextured[HMB_SPEC_TEXTURE_PATH + 1] = {};
      EXPECT_NO_THROW(vk::ComputeKernel(context(), kernel.name, layout.pushBytes, untextured))
          << kernel.name << " without the texture path";
    }
  }
}

TEST_F(KernelPipelinesTest, ReflectionReadsWhatEachKernelDeclares) {
  uint32_t addressBuilds = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    const vk::KernelInterface reflected = vk::reflectKernel(kernel);
    const kernels::KernelFacts& layout = layoutOf(kernel.name);
    EXPECT_LE(reflected.pushConstantBytes, layout.pushBytes) << kernel.name;
    EXPECT_GE(reflected.localSize[0] * reflected.localSize[1] * reflected.localSize[2], 1u) << kernel.name;
    if (!isAddressBuild(kernel.name)) {
      EXPECT_EQ(reflected.storageBufferBindings.size(), layout.storageBindings()) << kernel.name;
      EXPECT_EQ(reflected.texelBufferBindings.size(), layout.texelBindings) << kernel.name;
      EXPECT_EQ(reflected.sampledImageBindings.size() + reflected.storageImageBindings.size(), layout.imageBindings)
          << kernel.name;
      EXPECT_EQ(reflected.otherDescriptors, 0u) << kernel.name;
      EXPECT_FALSE(reflected.usesDeviceAddresses) << kernel.name << ": plain builds run without device addresses";
      continue;
    }
    EXPECT_TRUE(reflected.usesDeviceAddresses) << kernel.name;
    // An address build binds each group (trace scene, shading scene, image layer) as one table.
    ++addressBuilds;
    EXPECT_LE(reflected.storageBufferBindings.size(), 8u) << kernel.name;
    EXPECT_LT(reflected.storageBufferBindings.size(), layout.bindings) << kernel.name;
  }
  EXPECT_GE(addressBuilds, 4u);
  // encode_display: two buffers, one group of 8x8, its parameters (shared header).
  const vk::KernelInterface encode = vk::reflectKernel(vk::findKernel("output/encode_display"));
  EXPECT_EQ(encode.storageBufferBindings, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(encode.pushConstantBytes, sizeof(gpu::EncodeDisplayParams));
}

TEST_F(KernelPipelinesTest, HostsThatDisagreeWithTheKernelAreOneLineErrors) {
  const kernels::KernelFacts& layout = layoutOf("output/encode_display");
  expectError([&] { vk::ComputeKernel(context(), layout.name, layout.pushBytes - 4); },
              "bytes of push constants but its host passes");
  const vk::ComputeKernel kernel(context(), layout.name, layout.pushBytes);
  vk::Buffer one(context(), 64, vk::MemoryUse::Device, "test buffer");
  vk::FrameRecorder frame(context());
  frame.begin();
  const gpu::EncodeDisplayParams params{};
  // Buffers go to the binding numbers the kernel's header names, each once, all of them.
  const vk::Binding linear{HMB_ENCODE_DISPLAY_BINDING_LINEAR, &one}, rgba8{HMB_ENCODE_DISPLAY_BINDING_RGBA8, &one};
  expectError([&] { frame.dispatch("encode-display", kernel, {linear}, params, {1, 1, 1}); },
              "pass 'encode-display' (kernel 'output/encode_display') leaves binding 1 unbound");
  expectError([&] { frame.dispatch("encode-display", kernel, {linear, linear, rgba8}, params, {1, 1, 1}); },
              "binds binding 0 twice");
  expectError([&] { frame.dispatch("encode-display", kernel, {linear, rgba8, {7, &one}}, params, {1, 1, 1}); },
              "binds binding 7, which the kernel does not declare");
  expectError([&] { frame.dispatch("encode-display", kernel, {linear, {HMB_ENCODE_DISPLAY_BINDING_RGBA8, nullptr}},
                                   params, {1, 1, 1}); },
              "binds an empty buffer at binding 1");
}

// A kernel is made once per context: a second pass asking for it with the same push constants
// and specialization shares the pipeline; another specialization, or another context, makes its
// own; a failed build keeps nothing.
TEST_F(KernelPipelinesTest, EachKernelIsMadeOncePerContextAndSpecialization) {
  const kernels::KernelFacts& layout = layoutOf("bvh/build_level");
  // The GPU shape of the level kernel (shared atomics) at two workgroup sizes.
  const uint32_t eightLanes[] = {8u, 0u};
  const uint32_t sixteenLanes[] = {16u, 0u};
  const vk::ComputeKernel first(context(), layout.name, layout.pushBytes, eightLanes);
  const size_t kept = context().kernelStore().size();
  const vk::ComputeKernel again(context(), layout.name, layout.pushBytes, eightLanes);
  EXPECT_EQ(first.pipeline(), again.pipeline());
  EXPECT_EQ(first.layout(), again.layout());
  EXPECT_EQ(context().kernelStore().size(), kept);
  const vk::ComputeKernel wider(context(), layout.name, layout.pushBytes, sixteenLanes);
  EXPECT_NE(first.pipeline(), wider.pipeline());
  EXPECT_EQ(context().kernelStore().size(), kept + 1);
  expectError([&] { vk::ComputeKernel(context(), layout.name, layout.pushBytes - 4, eightLanes); },
              "bytes of push constants but its host passes");
  EXPECT_EQ(context().kernelStore().size(), kept + 1);
  vk::ContextOptions options;
  options.validation = true;
  const vk::Context other(options);
  const vk::ComputeKernel elsewhere(other, layout.name, layout.pushBytes, eightLanes);
  EXPECT_NE(elsewhere.pipeline(), first.pipeline());
  EXPECT_EQ(other.kernelStore().size(), 1u);
  EXPECT_EQ(other.validationErrors(), 0u);
}

// A device that takes fewer storage buffers per stage than the widest kernel: a kernel whose
// plain build binds more runs its address build where it has one that fits, and pipeline
// creation refuses the others in one line naming the kernel and the limit.
// Every build of every kernel declares SignedZeroInfNanPreserve for 32-bit floats
// (kernels/shared/float_controls.glsl): without it a driver may fold the kernels' isnan and
// isinf tests away, and bad input would reach the images.
TEST(KernelFloatControlsTest, EveryEmbeddedKernelKeepsNanAndInfinity) {
  ASSERT_FALSE(vk::embeddedKernels().empty());
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels())
    EXPECT_TRUE(keepsNanAndInfinity(std::span(kernel.words, kernel.wordCount)))
        << kernel.name << " does not keep NaN and infinity in 32-bit floats";
}

TEST(KernelLimitsTest, APretendDeviceWithFewerStorageBuffersTakesAddressBuildsOrRefusesInOneLine) {
  uint32_t widest = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels())
    widest = std::max(widest, uint32_t(vk::reflectKernel(kernel).storageBufferBindings.size()));
  ASSERT_GE(widest, 2u);
  const uint32_t limit = widest - 1;
  vk::ContextOptions options;
  options.validation = true;
  options.storageBufferLimit = limit;
  vk::Context small(options);
  ASSERT_EQ(small.limits().maxPerStageDescriptorStorageBuffers, limit);
  uint32_t switched = 0, refused = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    if (isAddressBuild(kernel.name)) continue;
    const kernels::KernelFacts& layout = layoutOf(kernel.name);
    if (layout.has(kernels::kInt64Atomics) && !small.info().int64BufferAtomics) continue;
    const vk::EmbeddedKernel* byAddress = vk::findKernelIfBuilt(std::string(kernel.name) + std::string(vk::kByAddressSuffix));
    if (layout.storageBindings() <= limit) {
      const vk::ComputeKernel built(small, kernel.name, layout.pushBytes);
      EXPECT_FALSE(built.bindsByAddress()) << kernel.name;
    } else if (byAddress && vk::reflectKernel(*byAddress).storageBufferBindings.size() <= limit &&
               small.info().bufferDeviceAddress) {
      ++switched;
      const vk::ComputeKernel built(small, kernel.name, layout.pushBytes);
      EXPECT_TRUE(built.bindsByAddress()) << kernel.name;
      EXPECT_LE(built.storageBufferCount(), limit) << kernel.name;
    } else {
      ++refused;
      expectError([&] { vk::ComputeKernel(small, kernel.name, layout.pushBytes); },
                  "kernel '" + std::string(kernel.name) + "' needs " + std::to_string(layout.storageBindings()) +
                      " storage buffers in one stage; the device allows " + std::to_string(limit) +
                      " (maxPerStageDescriptorStorageBuffers)");
    }
  }
  EXPECT_GE(switched + refused, 1u);
  EXPECT_EQ(small.validationErrors(), 0u);
}

// Mali and other GPUs allow 8 storage buffers per stage: every kernel fits there, through its
// address build where it has one, save those still listed here (docs/devices.md).
// Every kernel builds on a device with 8 storage buffers per stage (Mali's limit): plain builds
// fit, and the kernels that bind groups of buffers switch to their address builds.
TEST(KernelLimitsTest, EveryKernelBuildsOnADeviceWithEightStorageBuffers) {
  constexpr uint32_t kMali = 8;
  vk::ContextOptions options;
  options.validation = true;
  options.storageBufferLimit = kMali;
  vk::Context small(options);
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    if (isAddressBuild(kernel.name)) continue;
    const kernels::KernelFacts& layout = layoutOf(kernel.name);
    if (layout.has(kernels::kInt64Atomics) && !small.info().int64BufferAtomics) continue;
    const bool hasAddressBuild =
        vk::findKernelIfBuilt(std::string(kernel.name) + std::string(vk::kByAddressSuffix)) != nullptr;
    if (!hasAddressBuild) {
      EXPECT_LE(layout.storageBindings(), kMali) << kernel.name;
    } else if (!small.info().bufferDeviceAddress) {
      continue;
    }
    EXPECT_NO_THROW({
      const vk::ComputeKernel built(small, kernel.name, layout.pushBytes);
      EXPECT_LE(built.storageBufferCount(), kMali) << kernel.name;
    }) << kernel.name;
  }
  EXPECT_EQ(small.validationErrors(), 0u);
}

// A kernel built per combination of its switches: each combination once, each its own build,
// and more switches than constant ids fit in is a one-line error.
using KernelVariantsTest = VulkanTest;

TEST_F(KernelVariantsTest, EachCombinationOfSwitchesIsBuiltOnce) {
  const vk::KernelVariants gather(context(), kernels::kernel("mblur/gather"));
  const vk::ComputeKernel& straight = gather.with({false, false, true});
  EXPECT_EQ(&gather.with({false, false, true}), &straight);
  const vk::ComputeKernel& curved = gather.with({false, true, true});
  EXPECT_NE(&curved, &straight);
  EXPECT_EQ(&gather.with({false, true, true}), &curved);
  EXPECT_NE(&gather.with({true, false, true}), &straight);
  EXPECT_EQ(curved.bindings(), straight.bindings());
  std::initializer_list<bool> tooMany = {true, true, true, true, true, true, true, true, true, true, true,
                                         true, true, true, true, true, true, true, true, true, true, true,
                                         true, true, true, true, true, true, true, true, true, true, true};
  expectError([&] { gather.with(tooMany); }, "more than 32");
}

}  // namespace
}  // namespace hmb::test
