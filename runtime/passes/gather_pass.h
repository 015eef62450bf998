// Host side of kernels/mblur/gather.comp: the post-process gather, McGuire et al. 2012's
// reconstruction with the paper's weights, centred or adapted range (the "mcguire" filter).
#pragma once

#include <cstdint>
#include <string_view>

#include "hmblur/buffer.h"
#include "hmblur/post_process_settings.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/passes/gather_filter.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/kernel_variants.h"

namespace hmb::passes {

// Inside the hybrid's ray mask, the weights composite scales McGuire's weights (paper,
// section 4); 1 and 1 leave them as they are.
struct MaskWeights {
  float backgroundBoost = 1.0f;
  float foregroundDivide = 1.0f;
};

// The parameters every McGuire gather of a width x height image takes from the settings (the
// post-process gather, the hybrid's background gather and composite, and its ray mask, which
// must find the pixels they blur as they blur them).
gpu::GatherParams gatherParams(const PostProcessSettings& settings, uint32_t width, uint32_t height,
                               MaskWeights mask = {});

class GatherPass final : public GatherFilter {
 public:
  static constexpr const char* kName = "gather";
  // Before it, the image's 8 x 8 blocks are sorted into moving and still
  // (kernels/mblur/list_gather_blocks.comp); after it the still ones keep their own colour
  // (copy_still_blocks.comp). The gather runs over the moving blocks alone.
  static constexpr const char* kClearBlocks = "clear-gather-blocks";
  static constexpr const char* kListBlocks = "list-gather-blocks";
  static constexpr const char* kCopyStillBlocks = "copy-still-blocks";
  explicit GatherPass(const vk::Context& context);
  std::string_view passName() const override { return kName; }
  void plan(FramePlan& plan) const override;
  // Uses the McGuire fields of settings whatever settings.filter.
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
              const vk::Buffer& output, const PostProcessSettings& settings) const override;
  // The same outside the hybrid's ray mask (uint per pixel, 0 outside): the mask's pixels are
  // left as they are, for its composite.
  void recordOutsideMask(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                         const vk::Buffer& output, const PostProcessSettings& settings,
                         const vk::Buffer& mask) const;

 private:
  void recordWith(bool outsideMask, vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                  const vk::Buffer& neighborMax, const vk::Buffer& output, const PostProcessSettings& settings,
                  const vk::Buffer& mask) const;

  // Sorts the blocks of a width x height image into blocks_ (sized here as needed); returns
  // how many there are.
  uint32_t recordBlockLists(vk::FrameRecorder& frame, uint32_t width, uint32_t height, uint32_t tileSize,
                        const vk::Buffer& neighborMax) const;

  const vk::Context& context_;
  vk::KernelVariants kernels_;  // by outside the mask, path and range
  vk::ComputeKernel listBlocks_;
  vk::ComputeKernel copyStillBlocks_;
  mutable vk::Buffer blocks_, blockCounters_;
};

}  // namespace hmb::passes
