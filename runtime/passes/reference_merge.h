// The merge of a reference render's shards (hmblur merge): each shard's part (a partial file,
// reference_partial.h) holds its nodes of the sum tree; the merge loads them one at a time and
// adds them up in the tree's order (SumStack on DeviceSumSlots), so the image is the single
// render's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec4.hpp>

#include "runtime/passes/reference_partial.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

// What a merge of parts gives (hmblur merge).
struct MergedReference {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::vec4> color;  // the mean, as a render's `color`
  std::vector<ReferencePartial> parts;  // in the order given
  std::vector<uint32_t> missingShards;
  uint32_t samples = 0;      // N of the render
  uint32_t samplesHeld = 0;  // of them, in the parts
  vk::FrameTimings timings;
};

// Merges the parts of one reference render (each a shard's partial file, in any order): the
// image a single render of all its samples gives, bit for bit, on the same device and driver.
// Throws hmb::Error in one line for parts of different renders or versions, a shard given
// twice, and, unless `allowPartial` (which merges the samples the parts hold), a missing or
// unfinished shard.
MergedReference mergeReferenceParts(const vk::Context& context, vk::FrameRecorder& frame,
                                    const std::vector<std::filesystem::path>& parts, bool allowPartial);

}  // namespace hmb::passes
