// Settings of the distributed-ray-traced reference (ReferenceStage), the choices a user makes of
// them, and what a long render reports as it goes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "hmblur/setting.h"

namespace hmb::passes {

// One of `count` runs of consecutive samples (passes/reference_sum_tree.h's shardSamples),
// 0-based: shards rendered apart merge to the whole render's image bit for bit.
struct ReferenceShard {
  uint32_t index = 0;
  uint32_t count = 1;
  bool operator==(const ReferenceShard&) const = default;
};

struct ReferenceSettings {
  uint32_t samplesPerPixel = 256;
  uint32_t seed = 1;
  bool pixelJitter = false;       // a random point in the pixel per sample instead of its centre
  uint32_t timesPerBatch = 64;    // shutter times whose transforms are on the device at once
  bool sampleStillPixelsOnce = true;  // with a still camera: pixels nothing moving crosses take one sample
  std::filesystem::path checkpoint;  // empty: none; else resumed from when it matches, rewritten every timesPerBatch samples
  // The samples to take; with more than one shard the sums are kept in `checkpoint` (the part a
  // merge reads), and the image is the mean of the shard's samples alone.
  ReferenceShard shard;
};

// Every reference setting a user can choose, each described once (include/hmblur/setting.h). None
// derives from the scene: the choices are the settings themselves.
const settings::Table<ReferenceSettings, ReferenceSettings>& referenceSettingTable();

// Throws hmb::Error (one line) for settings that cannot render.
void validateReferenceSettings(const ReferenceSettings& settings);

struct ReferenceProgress {
  uint32_t samplesDone = 0;
  uint32_t samplesTotal = 0;
  uint32_t samplesResumed = 0;  // taken from the checkpoint, not rendered by this call
  // With a still camera, only pixels whose ray meets a moving instance's swept box take more
  // than one sample (the rest see one surface all shutter long); absent when all pixels do.
  std::optional<uint64_t> movingPixels;
  // Samples taken by this call, over all pixels: the first sample takes every pixel, later
  // ones only the moving pixels where they are listed (none on a still frame).
  uint64_t pixelSamples = 0;
};

}  // namespace hmb::passes
