// A reference render split into shards (ReferenceSettings::shard, each shard's part its
// checkpoint file) and merged (passes::mergeReferenceParts): the merged image is the single
// render's bit for bit at 160x90 for 1, 2, 3 and 7 shards given in any order, with a still or a
// moving camera, pixel jitter and a deforming mesh; a shard stopped midway resumes from its
// part; and parts that do not make one render are refused in one line each. fold_sums, the
// kernel that adds the parts' nodes, against the host's float additions.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "kernels/manifest.h"
#include "kernels/reference/reference_layout.h"
#include "runtime/passes/reference_merge.h"
#include "runtime/passes/reference_partial.h"
#include "runtime/passes/reference_stage.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/expect_error.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;
using ReferenceShardsTest = VulkanTest;

constexpr uint32_t kWidth = 160, kHeight = 90;

RenderSettings referenceSettings(uint32_t spp) {
  RenderSettings settings;
  settings.method = Method::Reference;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.reference.samplesPerPixel = spp;
  return settings;
}

std::vector<float> beauty(const RenderResult& result) { return result.image.find("")->values; }

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// A folder of its own for each use, emptied.
fs::path partsFolder(const std::string& name) {
  const fs::path folder = fs::path(testing::TempDir()) / ("hmb_reference_shards_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

// Renders every shard of `count` into the folder; the parts' paths by shard.
std::vector<fs::path> renderParts(Renderer& renderer, const scene::Scene& scene, RenderSettings settings,
                                  uint32_t count, const fs::path& folder) {
  std::vector<fs::path> parts;
  for (uint32_t i = 0; i < count; ++i) {
    settings.reference.shard = {i, count};
    settings.reference.checkpoint = folder / ("part-" + std::to_string(i) + ".hmbpart");
    renderer.render(scene, settings);
    parts.push_back(settings.reference.checkpoint);
  }
  return parts;
}

passes::MergedReference merge(const std::vector<fs::path>& parts, bool allowPartial = false) {
  vk::FrameRecorder frame(VulkanTest::context());
  return passes::mergeReferenceParts(VulkanTest::context(), frame, parts, allowPartial);
}

std::vector<float> mergedBeauty(const std::vector<fs::path>& parts) {
  const passes::MergedReference merged = merge(parts);
  EXPECT_EQ(merged.width, kWidth);
  EXPECT_EQ(merged.height, kHeight);
  EXPECT_EQ(merged.samplesHeld, merged.samples);
  std::vector<float> values;
  for (const glm::vec4& c : merged.color) values.insert(values.end(), {c.r, c.g, c.b, c.a});
  return values;
}

// Every split of the scene's render, its parts merged as given, reversed and shuffled.
void expectShardsMergeToTheSingleRender(const scene::Scene& scene, const RenderSettings& settings,
                                        const std::vector<uint32_t>& shardCounts, const std::string& what) {
  static Renderer renderer(VulkanTest::context());
  const std::vector<float> single = beauty(renderer.render(scene, settings));
  std::mt19937 random(5);
  for (const uint32_t count : shardCounts) {
    std::vector<fs::path> parts = renderParts(renderer, scene, settings, count, partsFolder(what));
    EXPECT_TRUE(sameBits(mergedBeauty(parts), single)) << what << ", " << count << " shards";
    std::reverse(parts.begin(), parts.end());
    EXPECT_TRUE(sameBits(mergedBeauty(parts), single)) << what << ", " << count << " shards reversed";
    std::shuffle(parts.begin(), parts.end(), random);
    EXPECT_TRUE(sameBits(mergedBeauty(parts), single)) << what << ", " << count << " shards shuffled";
  }
}

TEST_F(ReferenceShardsTest, ShardsMergeToTheSingleRenderBitForBit) {
  // Living room: a still camera, so pixels nothing moving crosses take sample 0 alone.
  const scene::Scene livingRoom = scene::loadScene("living-room");
  RenderSettings settings = referenceSettings(16);
  settings.reference.timesPerBatch = 5;  // shards start and end inside batches
  {
    Renderer renderer(context());
    ASSERT_TRUE(renderer.render(livingRoom, settings).reference->movingPixels.has_value());
  }
  expectShardsMergeToTheSingleRender(livingRoom, settings, {1, 2, 3, 7}, "living-room");
  // Bistro: a moving camera, every pixel every sample.
  expectShardsMergeToTheSingleRender(scene::loadScene("bistro"), referenceSettings(16), {1, 2, 3, 7}, "bistro");
}

TEST_F(ReferenceShardsTest, JitteredAndDeformingShardsMergeToTheSingleRender) {
  RenderSettings jittered = referenceSettings(12);
  jittered.reference.pixelJitter = true;
  expectShardsMergeToTheSingleRender(scene::loadScene("temple"), jittered, {3, 12}, "temple-jittered");
  const scene::Scene arm = scene::loadScene((fs::path(HMB_DEFORMING_SCENES_DIR) / "skinned-arm.gltf").string(),
                                            scene::ShutterChoice{.fps = 120.0f, .exposureSeconds = 1.0f / 60.0f});
  expectShardsMergeToTheSingleRender(arm, referenceSettings(6), {2, 3}, "skinned-arm");
}

// A device whose storage buffers hold 1.5 MiB, less than three 320x180 sums (0.9 MB each),
// keeps its ten slots in bands of rows, a buffer each: the image and the merge are the same bits
// as with one band.
TEST(ReferenceShardsBandsTest, SumsInBandsOfRowsAddUpAlike) {
  const scene::Scene scene = scene::loadScene("living-room");
  RenderSettings settings = referenceSettings(9);
  settings.width = 320;
  settings.height = 180;
  const std::vector<float> oneBand = beauty(Renderer(VulkanTest::context()).render(scene, settings));
  vk::ContextOptions options;
  options.validation = true;
  options.storageBufferRangeLimit = 3u << 19;
  vk::Context narrow(options);
  Renderer renderer(narrow);
  EXPECT_TRUE(sameBits(beauty(renderer.render(scene, settings)), oneBand));
  const fs::path folder = partsFolder("bands");
  std::vector<fs::path> parts;
  for (uint32_t i = 0; i < 3; ++i) {
    settings.reference.shard = {i, 3};
    settings.reference.checkpoint = folder / ("part-" + std::to_string(i) + ".hmbpart");
    renderer.render(scene, settings);
    parts.push_back(settings.reference.checkpoint);
  }
  vk::FrameRecorder frame(narrow);
  const passes::MergedReference merged = passes::mergeReferenceParts(narrow, frame, parts, false);
  std::vector<float> values;
  for (const glm::vec4& c : merged.color) values.insert(values.end(), {c.r, c.g, c.b, c.a});
  EXPECT_TRUE(sameBits(values, oneBand));
  EXPECT_EQ(narrow.validationErrors(), 0u);
  vk::FrameTimings timings;
  const passes::ReferenceSumKernels kernels(narrow);
  const passes::DeviceSumSlots slots(narrow, frame, kernels, 320, 180, timings);
  EXPECT_EQ(slots.count(), 10u);
  EXPECT_EQ(slots.bands().size(), 6u);  // 30 rows of ten slots in 1.5 MiB
  // Where one buffer holds three slots, one band of as many slots as it holds.
  EXPECT_EQ(passes::DeviceSumSlots(narrow, frame, kernels, kWidth, kHeight, timings).bands().size(), 1u);
  // The slots of one row must fit in one buffer.
  expectError([&] { passes::DeviceSumSlots(narrow, frame, kernels, 40000, 2, timings); }, "use a narrower image");
}

TEST_F(ReferenceShardsTest, AShardStoppedMidwayResumesFromItsPart) {
  const scene::Scene scene = scene::loadScene("living-room");
  Renderer renderer(context());
  RenderSettings settings = referenceSettings(24);
  settings.reference.timesPerBatch = 4;
  const std::vector<float> single = beauty(renderer.render(scene, settings));
  const fs::path folder = partsFolder("resume");
  std::vector<fs::path> parts = renderParts(renderer, scene, settings, 3, folder);

  // Shard 1/3 takes samples 8..15 in two batches; stopped during the second, its part holds the
  // first...
  RenderSettings stopped = settings;
  stopped.reference.shard = {1, 3};
  stopped.reference.checkpoint = folder / "part-1-again.hmbpart";
  stopped.onProgress = [](const passes::ReferenceProgress& p) {
    if (p.samplesDone == 6) throw std::runtime_error("stopped");
  };
  EXPECT_THROW(renderer.render(scene, stopped), std::runtime_error);
  // ... and the part it left is refused unfinished, or merged as what it holds.
  parts[1] = stopped.reference.checkpoint;
  expectError([&] { merge(parts); }, "unfinished (4 of 8 samples)");
  EXPECT_EQ(merge(parts, true).samplesHeld, 20u);

  uint32_t rendered = 0;
  stopped.onProgress = [&](const passes::ReferenceProgress&) { ++rendered; };
  const RenderResult resumed = renderer.render(scene, stopped);
  EXPECT_EQ(resumed.reference->samplesResumed, 4u);
  EXPECT_EQ(rendered, 4u);
  EXPECT_TRUE(sameBits(mergedBeauty(parts), single));
}

// A part written with one thing changed in its header, its sums kept.
fs::path rewrittenPart(const fs::path& part, const fs::path& to, void (*change)(passes::ReferencePartial&)) {
  const passes::ReferencePartial original = passes::readReferencePartial(part);
  passes::ReferencePartial header = original;
  change(header);
  passes::writeReferencePartial(to, header, [&](size_t i) {
    std::vector<glm::vec4> sums(original.pixels);
    passes::readReferencePartialNode(part, original, i, sums);
    return sums;
  });
  return to;
}

TEST_F(ReferenceShardsTest, PartsThatDoNotMakeOneRenderAreRefusedInOneLine) {
  const scene::Scene scene = scene::loadScene("living-room");
  Renderer renderer(context());
  const RenderSettings settings = referenceSettings(8);
  const fs::path folder = partsFolder("refusals");
  const std::vector<fs::path> parts = renderParts(renderer, scene, settings, 4, folder);
  const auto otherPart = [&](const std::string& name, const scene::Scene& s, RenderSettings changed, uint32_t count) {
    const fs::path sub = folder / name;
    fs::create_directories(sub);
    return renderParts(renderer, s, changed, count, sub);
  };

  RenderSettings otherSeed = settings;
  otherSeed.reference.seed = 9;
  expectError([&] { merge({parts[0], parts[1], otherPart("seed", scene, otherSeed, 4)[2], parts[3]}); },
              "another render than '" + parts[0].string() + "': seed 9 against 1");
  RenderSettings otherSpp = settings;
  otherSpp.reference.samplesPerPixel = 12;
  expectError([&] { merge({parts[0], otherPart("spp", scene, otherSpp, 4)[1]}); }, "spp 12 against 8");
  RenderSettings otherSize = settings;
  otherSize.width = 96;
  expectError([&] { merge({parts[0], otherPart("size", scene, otherSize, 4)[1]}); }, "width 96 against 160");
  expectError([&] { merge({parts[0], otherPart("scene", scene::loadScene("temple"), settings, 4)[1]}); },
              "scene \"temple\" against \"living-room\"");
  expectError([&] { merge({parts[0], otherPart("split", scene, settings, 2)[1]}); }, "merge the parts of one split");

  expectError([&] { merge({parts[0], parts[1], parts[1], parts[2], parts[3]}); }, "shard 1/4 is given twice");
  expectError([&] { merge({parts[3], parts[0]}); }, "shards 1/4, 2/4 are missing (--allow-partial");
  const passes::MergedReference partial = merge({parts[3], parts[0]}, true);
  EXPECT_EQ(partial.samplesHeld, 4u);
  EXPECT_EQ(partial.missingShards, (std::vector<uint32_t>{1, 2}));

  const fs::path otherVersion = rewrittenPart(parts[2], folder / "version.hmbpart",
                                              [](passes::ReferencePartial& h) { h.version = "hmblur 0.0.1 (older)"; });
  expectError([&] { merge({parts[0], parts[1], otherVersion, parts[3]}); }, "was written by hmblur 0.0.1 (older)");
  // A part claiming another shard's place holds nodes that are not its own shard's.
  const fs::path misplaced =
      rewrittenPart(parts[2], folder / "misplaced.hmbpart", [](passes::ReferencePartial& h) { h.shardIndex = 1; });
  expectError([&] { merge({parts[0], misplaced}); }, "damaged: its shard does not add up");

  // Files that are no part: missing, truncated, of the older format, foreign, damaged.
  expectError([&] { merge({folder / "none.hmbpart"}); }, "cannot be read");
  const fs::path truncated = folder / "truncated.hmbpart";
  fs::copy_file(parts[1], truncated);
  fs::resize_file(truncated, fs::file_size(truncated) - 100);
  expectError([&] { merge({parts[0], truncated}); }, "is truncated");
  fs::resize_file(truncated, 12);
  expectError([&] { merge({truncated}); }, "not a reference partial");
  const auto writeFile = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(folder / name, std::ios::binary) << bytes;
    return folder / name;
  };
  expectError([&] { merge({writeFile("older.hmbpart", std::string("HMBREF1\0", 8) + std::string(16, '\0'))}); },
              "older hmblur (format 1)");
  expectError([&] { merge({writeFile("foreign.hmbpart", "P6\n160 90\n255\n" + std::string(300, 'x'))}); },
              "not a reference partial");
  std::string damaged = std::string("HMBREF2\0", 8);
  const std::string header = "{\"identity\": 3}";
  const uint64_t length = header.size();
  damaged.append(reinterpret_cast<const char*>(&length), sizeof(length));
  expectError([&] { merge({writeFile("damaged.hmbpart", damaged + header)}); }, "damaged");
  expectError([&] { merge({}); }, "no parts to merge");
  fs::remove_all(folder);
}

TEST_F(ReferenceShardsTest, AShardNeedsAFileAndAShareOfTheSamples) {
  Renderer renderer(context());
  const scene::Scene scene = scene::loadScene("living-room");
  RenderSettings settings = referenceSettings(4);
  settings.reference.shard = {1, 2};
  expectError([&] { renderer.render(scene, settings); }, "give it a checkpoint");
  settings.reference.checkpoint = partsFolder("settings") / "part.hmbpart";
  settings.reference.shard = {0, 5};
  expectError([&] { renderer.render(scene, settings); }, "5 shards of 4 samples per pixel would leave some empty");
  settings.reference.shard = {2, 2};
  expectError([&] { renderer.render(scene, settings); }, "I must be below K");
}

// fold_sums against the host's float additions, in the same order, on values that round, cancel,
// overflow to infinity (and to NaN, infinities of both signs added) and carry signed zeros; no
// subnormals (a device may flush them): every value is a multiple of 2^-88.
TEST_F(ReferenceShardsTest, FoldSumsAddsAsTheHostDoes) {
  constexpr uint32_t kPixels = 1000, kSlots = 6;
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-60, 127);
  std::vector<glm::vec4> sums(kPixels * kSlots);
  for (glm::vec4& s : sums)
    for (int c = 0; c < 4; ++c) {
      const float r = unit(random);
      s[c] = std::abs(r) < 0.05f ? (r < 0 ? -0.0f : 0.0f) : std::ldexp(r, exponent(random));
    }
  std::vector<glm::uvec4> ops;
  std::uniform_int_distribution<uint32_t> slot(0, kSlots - 1);
  while (ops.size() < 24) {
    const uint32_t left = slot(random), right = slot(random);
    if (left != right) ops.emplace_back(left, right, 0u, 0u);
  }
  std::vector<glm::vec4> expected = sums;
  for (const glm::uvec4& op : ops)
    for (uint32_t p = 0; p < kPixels; ++p) expected[op.x * kPixels + p] += expected[op.y * kPixels + p];

  vk::Context& ctx = context();
  const vk::Buffer sumBuffer = vk::uploadedBuffer(ctx, sums, "test sums");
  const vk::Buffer opBuffer = vk::uploadedBuffer(ctx, ops, "test fold steps");
  const vk::ComputeKernel kernel(ctx, kernels::kernel("reference/fold_sums"));
  vk::FrameRecorder frame(ctx);
  frame.begin();
  frame.dispatch("fold-sums", kernel, {{HMB_FOLD_SUMS_BINDING_SUMS, &sumBuffer}, {HMB_FOLD_SUMS_BINDING_OPS, &opBuffer}},
                 gpu::FoldSumsParams{kPixels, static_cast<uint32_t>(ops.size()), 0u, 0u},
                 vk::foldedGroups(vk::groupsFor(kPixels, HMB_FOLD_SUMS_GROUP)));
  frame.submitAndWait();
  const std::vector<glm::vec4> got = sumBuffer.download<glm::vec4>();
  size_t infinities = 0, differing = 0;
  for (size_t i = 0; i < got.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      infinities += std::isinf(expected[i][c]);
      // NaN's payload is the hardware's: any NaN is the same result.
      if (std::isnan(expected[i][c]))
        differing += !std::isnan(got[i][c]);
      else
        differing += std::bit_cast<uint32_t>(got[i][c]) != std::bit_cast<uint32_t>(expected[i][c]);
    }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(infinities, 0u) << "the values never overflowed: the case is not covered";
}

}  // namespace
}  // namespace hmb::test
