// The hybrid composites against the C++ reference on random and adversarial layers: the
// coverage form (mask_coverage's alpha and foreground over the background that
// reveal/gather_background.comp gathers and blends at mask pixels) and the weights form
// (reveal/composite.comp); and the background gather over a pixel list alone: exactly the listed
// pixels written, each as the full-frame gather writes it, also with more groups than one row of
// a dispatch holds, and the revealed layer read where the mask says so.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/gbuffer/gbuffer_layout.h"
#include "tests/hybrid/hybrid_harness.h"
#include "tests/hybrid/hybrid_reference.h"
#include "tests/mblur/mblur_harness.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace hybrid;
using mblur::Layer;
using passes::GatherRange;
using passes::HybridComposite;
using passes::PostProcessSettings;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

PostProcessSettings compositeSettings(uint32_t tileSize, uint32_t samples, uint32_t seed) {
  PostProcessSettings s;
  s.range = GatherRange::Adapted;
  s.tileSize = tileSize;
  s.samples = samples;
  s.seed = seed;
  s.softZExtent = 0.05f;
  return s;
}

// The paper's boosts inside the mask (the weights composite's).
constexpr passes::MaskWeights kMaskWeights{3.0f, 3.0f};

// The composite's inputs beside the layer: a mask, a background and object ids. The weights
// form takes the background as the blurred background B; the coverage form gathers B itself from
// the revealed layer (revealedLayer) where mask_coverage lists a pixel for the reveal.
struct CompositeCase {
  Layer layer;
  std::vector<uint32_t> mask;
  std::vector<glm::vec4> background;
  std::vector<uint32_t> objectId;
  std::optional<Layer> revealed;  // the coverage form's; default: the layer in the background's colours
};

// mblur's random layer (rectangles at one depth each over a noisy far background): each
// rectangle is one object (its depth names it), the background another; a few pixels carry
// a stray id so that samples of another object at the same depth occur. A third of the pixels
// are in the mask.
CompositeCase randomCase(uint32_t width, uint32_t height, std::mt19937& rng) {
  CompositeCase c;
  c.layer = mblur::randomLayer(width, height, rng);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const size_t pixels = c.layer.color.size();
  for (size_t i = 0; i < pixels; ++i) {
    const float depth = c.layer.normalDepth[i].w;
    c.objectId.push_back(depth < 9.0f ? 2u + uint32_t(depth * 1000.0f) : 1u);
    if (unit(rng) < 0.03f) c.objectId.back() = 7u;
    c.mask.push_back(unit(rng) < 0.33f ? 1u : 0u);
    c.background.emplace_back(unit(rng), unit(rng), unit(rng), 1.0f);
  }
  return c;
}

// Values no G-buffer should hold, in colour, background, depth and velocity.
void makeAdversarial(CompositeCase& c, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float colours[] = {kNaN, kInf, -kInf, 1e30f, -5.0f, 70000.0f};
  const float depths[] = {kNaN, kInf, -kInf, 0.0f, 1e30f, 3e38f};
  const float velocities[] = {kNaN, kInf, 1e30f, -1e30f, 1e-31f, 0.3f};
  auto pick = [&](const auto& values) { return values[size_t(unit(rng) * std::size(values)) % std::size(values)]; };
  for (size_t i = 0; i < c.layer.color.size(); ++i) {
    if (unit(rng) < 0.05f) c.layer.color[i][int(unit(rng) * 4.0f) % 4] = pick(colours);
    if (unit(rng) < 0.05f) c.background[i][int(unit(rng) * 4.0f) % 4] = pick(colours);
    if (unit(rng) < 0.05f) c.layer.normalDepth[i].w = pick(depths);
    if (unit(rng) < 0.05f) c.layer.velocity[i] = {pick(velocities), pick(velocities)};
  }
}

// What the reveal found behind the case's pixels: by default the layer with the background's
// colours.
Layer revealedLayer(const CompositeCase& c) {
  if (c.revealed) return *c.revealed;
  Layer revealed = c.layer;
  revealed.color = c.background;
  revealed.shutterPaths.clear();
  return revealed;
}

std::vector<glm::vec4> runComposite(const CompositeCase& c, const std::vector<glm::vec4>& tiles,
                                    const PostProcessSettings& s, HybridComposite composite) {
  const Layer revealed = revealedLayer(c);
  GatherRun run;
  run.mask = &c.mask;
  run.objectId = &c.objectId;
  run.composite = composite;
  run.maskWeights = kMaskWeights;
  if (composite == HybridComposite::Coverage)
    run.revealed = &revealed;
  else
    run.background = &c.background;
  return runGather(VulkanTest::context(), c.layer, tiles, run, s);
}

// The coverage form's blurred background B: the post-process gather of the raster with the
// revealed layer in its place at the pixels mask_coverage lists for the reveal (those whose
// samples meet another object behind them), whose samples go straight.
std::vector<glm::vec4> coverageBackground(const CompositeCase& c, const std::vector<glm::vec4>& tiles,
                                          const PostProcessSettings& s) {
  const std::vector<MaskCoverage> coverage = maskCoverage(c.layer, c.mask, c.objectId, s);
  const Layer revealed = revealedLayer(c);
  Layer overlaid = c.layer;
  for (size_t i = 0; i < c.mask.size(); ++i) {
    if (c.mask[i] == 0u || !coverage[i].meetsBackground) continue;
    overlaid.color[i] = revealed.color[i];
    overlaid.normalDepth[i] = revealed.normalDepth[i];
    overlaid.velocity[i] = revealed.velocity[i];
    if (!overlaid.shutterPaths.empty()) overlaid.shutterPaths[i] = glm::uvec2(HMB_NO_SHUTTER_PATH);
  }
  return mblur::gather(overlaid, tiles, nullptr, s);
}

// Every output finite and within 1e-5 relative (colours are O(1)) of the reference, except
// pixels where a sample position rounds to the other neighbouring pixel on the device (a
// position a rounding step from a pixel edge): at most 0.1% of them. Returns how many mask
// pixels the composite changed from the plain gather (so a case can show it tested something).
size_t expectCompositeMatches(const CompositeCase& c, const PostProcessSettings& s, HybridComposite composite,
                              const std::string& what) {
  const std::vector<glm::vec4> tiles = mblur::referenceTiles(c.layer, s);
  const std::vector<glm::vec4> device = runComposite(c, tiles, s, composite);
  const std::vector<glm::vec4> reference =
      compositeGather(c.layer, tiles, c.mask,
                      composite == HybridComposite::Coverage ? coverageBackground(c, tiles, s) : c.background,
                      c.objectId, s, composite, kMaskWeights);
  const std::vector<glm::vec4> plain = mblur::gather(c.layer, tiles, &c.mask, s, kMaskWeights);
  EXPECT_TRUE(mblur::allFinite(device)) << what;
  size_t off = 0, changed = 0, maskPixels = 0;
  for (size_t i = 0; i < device.size(); ++i) {
    const float scale = std::max(
        {1.0f, std::abs(reference[i].x), std::abs(reference[i].y), std::abs(reference[i].z), std::abs(reference[i].w)});
    if (mblur::maxAbsDifference(device[i], reference[i]) > 1e-5f * scale) ++off;
    if (c.mask[i] != 0u) {
      ++maskPixels;
      if (mblur::maxAbsDifference(plain[i], reference[i]) > 1e-3f) ++changed;
    }
  }
  EXPECT_LE(off, device.size() / 1000) << what << ": " << off << " of " << device.size() << " pixels differ";
  EXPECT_GT(maskPixels, 0u) << what;
  return changed;
}

// The pixels whose mask value is `value`, listed as list_mask_blocks lists them: block by block
// (HMB_MASK_BLOCK square, from the image's corner), each block's pixels in row order. The
// blocks come in the order the device's list first reaches them (its atomics decide it), so
// the two lists are equal exactly when the device listed every such pixel once, kept each
// block's together and in row order.
std::vector<uint32_t> listedByBlocks(const std::vector<uint32_t>& maskValues, uint32_t width, uint32_t height,
                                     uint32_t value, const std::vector<uint32_t>& device) {
  const uint32_t blocksAcross = HMB_MASK_BLOCKS_ACROSS(width);
  const auto blockOf = [&](uint32_t pixel) {
    return pixel / width / HMB_MASK_BLOCK * blocksAcross + pixel % width / HMB_MASK_BLOCK;
  };
  std::vector<uint32_t> blocks;
  for (const uint32_t pixel : device)
    if (pixel < maskValues.size() && std::find(blocks.begin(), blocks.end(), blockOf(pixel)) == blocks.end())
      blocks.push_back(blockOf(pixel));
  std::vector<uint32_t> out;
  for (const uint32_t block : blocks) {
    const uint32_t x0 = block % blocksAcross * HMB_MASK_BLOCK, y0 = block / blocksAcross * HMB_MASK_BLOCK;
    for (uint32_t y = y0; y < std::min(y0 + HMB_MASK_BLOCK, height); ++y)
      for (uint32_t x = x0; x < std::min(x0 + HMB_MASK_BLOCK, width); ++x)
        if (maskValues[size_t(y) * width + x] == value) out.push_back(y * width + x);
  }
  // Pixels of blocks the device never reached: missing from its list.
  for (uint32_t i = 0; i < maskValues.size(); ++i)
    if (maskValues[i] == value && std::find(blocks.begin(), blocks.end(), blockOf(i)) == blocks.end()) out.push_back(i);
  return out;
}

using HybridCompositeTest = VulkanTest;

TEST_F(HybridCompositeTest, CoverageMatchesReferenceOnRandomLayers) {
  std::mt19937 rng(17);
  size_t changed = 0;
  for (const uint32_t tileSize : {8u, 20u})
    for (const uint32_t samples : {1u, 8u, 15u}) {
      const CompositeCase c = randomCase(71, 43, rng);
      changed +=
          expectCompositeMatches(c, compositeSettings(tileSize, samples, samples + tileSize), HybridComposite::Coverage,
                                 "tile " + std::to_string(tileSize) + " S " + std::to_string(samples));
    }
  EXPECT_GT(changed, 1000u) << "the composite should change most moving mask pixels";
}

// mask_coverage (ray_mask/mask_coverage.comp) on its own against the reference on random and
// adversarial layers, straight and curved: each mask pixel's foreground colour and alpha, and
// its mask value (revealed where a sample lies behind it); pixels outside the mask untouched.
TEST_F(HybridCompositeTest, MaskCoverageMatchesReferenceAndSplitsTheMask) {
  std::mt19937 rng(29);
  size_t revealed = 0, unrevealed = 0, partial = 0;
  for (uint32_t round = 0; round < 6; ++round) {
    CompositeCase c = randomCase(59 + 4 * round, 37, rng);
    if (round % 2 == 1) makeAdversarial(c, rng);
    PostProcessSettings s = compositeSettings(8u + 4u * round, 3u + 3u * round, round);
    if (round >= 4) {
      c.layer.shutterPaths = mblur::randomShutterPaths(c.layer.velocity, rng, 1.0f);
      s.motionPath = passes::MotionPath::Curved;
    }
    std::vector<glm::vec4> coverage;
    std::vector<uint32_t> maskValues, front, back;
    const Layer revealedLayerOfCase = revealedLayer(c);
    GatherRun run;
    run.mask = &c.mask;
    run.revealed = &revealedLayerOfCase;
    run.objectId = &c.objectId;
    run.coverageOut = &coverage;
    run.maskOut = &maskValues;
    run.frontOut = &front;
    run.backOut = &back;
    runGather(VulkanTest::context(), c.layer, mblur::referenceTiles(c.layer, s), run, s);
    // list_mask_blocks: the revealed pixels at the list's front and the others at its back,
    // each once, block by block (8 x 8 blocks in row order within each).
    EXPECT_EQ(front, listedByBlocks(maskValues, c.layer.width, c.layer.height, HMB_MASK_REVEALED, front))
        << "round " << round;
    EXPECT_EQ(back, listedByBlocks(maskValues, c.layer.width, c.layer.height, HMB_MASK_UNREVEALED, back))
        << "round " << round;
    const std::vector<MaskCoverage> reference = maskCoverage(c.layer, c.mask, c.objectId, s);
    size_t off = 0;
    for (size_t i = 0; i < c.mask.size(); ++i) {
      const std::string at = "round " + std::to_string(round) + " pixel " + std::to_string(i);
      if (c.mask[i] == 0u) {
        EXPECT_EQ(maskValues[i], HMB_MASK_NONE) << at;
        EXPECT_TRUE(std::isnan(coverage[i].x)) << at << ": written outside the mask";
        continue;
      }
      const glm::vec4 expected(reference[i].foreground, reference[i].alpha);
      const float scale = std::max({1.0f, std::abs(expected.x), std::abs(expected.y), std::abs(expected.z)});
      // As the composite's: a sample position a rounding step from a pixel edge may land on
      // the other pixel on the device.
      if (!(mblur::maxAbsDifference(coverage[i], expected) <= 1e-5f * scale)) {
        ++off;
        continue;
      }
      EXPECT_EQ(maskValues[i], reference[i].meetsBackground ? HMB_MASK_REVEALED : HMB_MASK_UNREVEALED) << at;
      (reference[i].meetsBackground ? revealed : unrevealed) += 1;
      partial += reference[i].alpha > 0.0f && reference[i].alpha < 1.0f;
    }
    EXPECT_LE(off, c.mask.size() / 1000) << "round " << round << ": " << off << " pixels differ";
  }
  EXPECT_GT(revealed, 100u);
  EXPECT_GT(unrevealed, 100u);
  EXPECT_GT(partial, 100u);
}

TEST_F(HybridCompositeTest, WeightsMatchReferenceOnRandomLayers) {
  std::mt19937 rng(19);
  size_t changed = 0;
  for (const uint32_t tileSize : {8u, 20u})
    for (const uint32_t samples : {1u, 15u}) {
      const CompositeCase c = randomCase(71, 43, rng);
      changed += expectCompositeMatches(c, compositeSettings(tileSize, samples, 3u), HybridComposite::Weights,
                                        "tile " + std::to_string(tileSize) + " S " + std::to_string(samples));
    }
  EXPECT_GT(changed, 150u);
}

// Both composites with the hybrid's default boost, which falls with the tile's speed.
TEST_F(HybridCompositeTest, CompositesWithABoostThatFallsWithTheSpeedMatchReference) {
  std::mt19937 rng(23);
  for (const HybridComposite composite : {HybridComposite::Coverage, HybridComposite::Weights}) {
    PostProcessSettings s = compositeSettings(16u, 15u, 5u);
    s.foregroundBoostPixels = passes::kHybridForegroundBoostPixels;
    const CompositeCase c = randomCase(67, 45, rng);
    EXPECT_GT(expectCompositeMatches(c, s, composite, "falling boost"), 100u);
  }
}

TEST_F(HybridCompositeTest, WeightsMatchReferenceWithTheCentredRange) {
  std::mt19937 rng(29);
  PostProcessSettings s = compositeSettings(12u, 15u, 9u);
  s.range = GatherRange::Centered;
  const CompositeCase c = randomCase(57, 39, rng);
  EXPECT_GT(expectCompositeMatches(c, s, HybridComposite::Weights, "centred"), 100u);
}

// The hybrid's post-process gather leaves the mask's pixels to the composite (they keep what
// the buffer held) and writes every other pixel exactly as the post-process gather does.
TEST_F(HybridCompositeTest, TheGatherOutsideTheMaskLeavesTheMaskAlone) {
  std::mt19937 rng(71);
  const CompositeCase c = randomCase(61, 37, rng);
  const PostProcessSettings s = compositeSettings(8, 9, 3);
  const std::vector<glm::vec4> tiles = mblur::referenceTiles(c.layer, s);
  GatherRun outside;
  outside.mask = &c.mask;
  outside.sentinel = glm::vec4(-7.0f);
  const std::vector<glm::vec4> device = runGather(context(), c.layer, tiles, outside, s);
  const std::vector<glm::vec4> whole = runGather(context(), c.layer, tiles, GatherRun{}, s);
  size_t inMask = 0;
  for (size_t i = 0; i < device.size(); ++i) {
    if (c.mask[i] != 0u) {
      ++inMask;
      EXPECT_EQ(device[i], outside.sentinel) << "mask pixel " << i;
    } else {
      EXPECT_EQ(device[i], whole[i]) << "pixel " << i;
    }
  }
  EXPECT_GT(inMask, device.size() / 5);
}

// Along curved paths (random paths, adversarial records among them): the coverage composite
// samples each mask pixel's own path and the gather outside the mask follows the curved path,
// both as the reference does; and the paths change the image.
TEST_F(HybridCompositeTest, CurvedPathsMatchTheReference) {
  std::mt19937 rng(37);
  size_t differ = 0;
  for (int round = 0; round < 3; ++round) {
    CompositeCase c = randomCase(61, 41, rng);
    if (round == 2) makeAdversarial(c, rng);
    PostProcessSettings s = compositeSettings(12u, 9u, uint32_t(round));
    c.layer.shutterPaths = mblur::randomShutterPaths(c.layer.velocity, rng, s.exposure * s.fps);
    s.motionPath = passes::MotionPath::Curved;
    expectCompositeMatches(c, s, HybridComposite::Coverage, "curved round " + std::to_string(round));
    const std::vector<glm::vec4> tiles = mblur::referenceTiles(c.layer, s);
    const std::vector<glm::vec4> curved = runComposite(c, tiles, s, HybridComposite::Coverage);
    PostProcessSettings straight = s;
    straight.motionPath = passes::MotionPath::Linear;
    const std::vector<glm::vec4> linear = runComposite(c, tiles, straight, HybridComposite::Coverage);
    for (size_t i = 0; i < curved.size(); ++i) differ += mblur::maxAbsDifference(curved[i], linear[i]) > 1e-3f;
  }
  EXPECT_GT(differ, 1000u);
}

TEST_F(HybridCompositeTest, CompositesMatchReferenceOnAdversarialLayers) {
  std::mt19937 rng(31);
  for (int round = 0; round < 3; ++round) {
    CompositeCase c = randomCase(53, 37, rng);
    makeAdversarial(c, rng);
    for (const HybridComposite composite : {HybridComposite::Coverage, HybridComposite::Weights})
      expectCompositeMatches(c, compositeSettings(10u, 15u, uint32_t(round)), composite,
                             "round " + std::to_string(round) + " " + std::string(passes::compositeName(composite)));
  }
}

// The coverage composite by hand: a pixel of object 2 (depth 1) moving 4 px right, its range
// covering two more pixels of object 2 and then object 1, far behind. With one sample per
// pixel at u = (i + 1 - j) / S the share on object 2 is known: alpha = (samples on it) / S and
// C = alpha (mean of the pixel and those samples) + (1 - alpha) B. Object 2's three pixels are
// in the mask and revealed as a still green surface beside object 1's still ones, so the
// background gather at the pixel meets only still samples: B is green.
TEST_F(HybridCompositeTest, CoverageByHand) {
  const uint32_t width = 12, height = 1;
  CompositeCase c;
  c.layer = mblur::stillLayer(width, height);
  for (uint32_t x = 0; x < width; ++x) {
    const bool front = x >= 2 && x <= 4;
    c.layer.color[x] = front ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    c.layer.normalDepth[x].w = front ? 1.0f : 10.0f;
    c.layer.velocity[x] = front ? glm::vec2(4.0f, 0.0f) : glm::vec2(0.0f);
    c.objectId.push_back(front ? 2u : 1u);
    c.mask.push_back(front ? 1u : 0u);
    c.background.emplace_back(0.0f, 1.0f, 0.0f, 1.0f);
  }
  c.revealed = mblur::stillLayer(width, height);
  for (uint32_t x = 0; x < width; ++x) {
    c.revealed->color[x] = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    c.revealed->normalDepth[x].w = 10.0f;
  }
  PostProcessSettings s = compositeSettings(4u, 8u, 0u);
  s.exposure = 1.0f / 120.0f;  // velocityScale E * fps = 1: 4 px per exposure
  const std::vector<glm::vec4> tiles = mblur::referenceTiles(c.layer, s);
  const std::vector<glm::vec4> device = runComposite(c, tiles, s, HybridComposite::Coverage);
  // Pixel 2's samples at 2.5 + 4u land on pixels 2 to 4 (object 2) for u < 0.625, and on 5
  // or 6 (object 1, far behind: none of them foreground) from there on.
  const float jitter = mblur::unitFromHash(mblur::mblurHash(2, 0, s.seed));
  uint32_t onObject = 0;
  for (uint32_t i = 0; i < s.samples; ++i) {
    const float u = (float(i) + 1.0f - jitter) / float(s.samples);
    if (std::floor(2.5f + 4.0f * u) <= 4.0f) ++onObject;
  }
  ASSERT_GT(onObject, 0u);
  ASSERT_LT(onObject, s.samples);
  const float alpha = float(onObject) / float(s.samples);
  // Foreground: the pixel and its samples on object 2 are all red.
  const glm::vec4 expected = alpha * glm::vec4(1, 0, 0, 1) + (1.0f - alpha) * glm::vec4(0, 1, 0, 1);
  EXPECT_LT(mblur::maxAbsDifference(device[2], expected), 1e-6f)
      << device[2].x << " " << device[2].y << " " << device[2].z << " alpha " << alpha;
  const std::vector<glm::vec4> reference = compositeGather(
      c.layer, tiles, c.mask, coverageBackground(c, tiles, s), c.objectId, s, HybridComposite::Coverage, kMaskWeights);
  EXPECT_LT(mblur::maxAbsDifference(reference[2], expected), 1e-6f);
}

// A random subset of the pixels, in random order.
std::vector<uint32_t> randomList(size_t pixels, float share, std::mt19937& rng) {
  std::vector<uint32_t> all(pixels);
  std::iota(all.begin(), all.end(), 0u);
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(size_t(float(pixels) * share));
  return all;
}

void expectListGather(const std::vector<glm::vec4>& listed, const std::vector<glm::vec4>& full,
                      const std::vector<uint32_t>& list, glm::vec4 sentinel, const std::string& what) {
  std::vector<bool> inList(full.size(), false);
  for (const uint32_t i : list) inList[i] = true;
  size_t wrong = 0;
  for (size_t i = 0; i < full.size(); ++i) {
    const glm::vec4 expected = inList[i] ? full[i] : sentinel;
    if (listed[i] != expected && ++wrong <= 5)
      ADD_FAILURE() << what << ": pixel " << i << (inList[i] ? " (listed)" : " (not listed)") << " is " << listed[i].x
                    << "," << listed[i].y << "," << listed[i].z << "," << listed[i].w;
  }
  EXPECT_EQ(wrong, 0u) << what;
}

TEST_F(HybridCompositeTest, PixelListGathersExactlyTheListedPixels) {
  std::mt19937 rng(37);
  const glm::vec4 sentinel(-3.0f, 123.0f, kInf, -0.0f);
  for (const float share : {0.0f, 0.01f, 0.37f, 1.0f}) {
    CompositeCase c = randomCase(67, 45, rng);
    const PostProcessSettings s = compositeSettings(10u, 15u, 4u);
    const std::vector<glm::vec4> tiles = mblur::referenceTiles(c.layer, s);
    const std::vector<uint32_t> list = randomList(c.layer.color.size(), share, rng);
    // The background gather of the hybrid stage (no pixel revealed): the post-process gather,
    // at the listed pixels alone.
    GatherRun run;
    run.sentinel = sentinel;
    const std::vector<glm::vec4> full = runGather(context(), c.layer, tiles, run, s);
    run.list = &list;
    expectListGather(runGather(context(), c.layer, tiles, run, s), full, list, sentinel,
                     "share " + std::to_string(share));
  }
}

// Along curved paths the background gather follows the raster's paths, and a revealed pixel has
// none: at the listed pixels it equals the post-process gather of the overlaid layer whose
// revealed pixels go straight.
TEST_F(HybridCompositeTest, TheBackgroundGatherFollowsTheRastersCurvedPaths) {
  std::mt19937 rng(41);
  CompositeCase c = randomCase(59, 37, rng);
  const CompositeCase other = randomCase(59, 37, rng);
  PostProcessSettings s = compositeSettings(10u, 11u, 2u);
  s.motionPath = passes::MotionPath::Curved;
  c.layer.shutterPaths = mblur::randomShutterPaths(c.layer.velocity, rng, s.exposure * s.fps);
  const size_t pixels = c.layer.color.size();
  std::vector<uint32_t> mask(pixels, HMB_MASK_NONE), list;
  Layer overlaid = c.layer;
  std::uniform_int_distribution<int> third(0, 2);
  for (uint32_t i = 0; i < pixels; ++i) {
    if (third(rng) == 0) {
      mask[i] = HMB_MASK_REVEALED;
      overlaid.color[i] = other.layer.color[i];
      overlaid.normalDepth[i] = other.layer.normalDepth[i];
      overlaid.velocity[i] = other.layer.velocity[i];
      overlaid.shutterPaths[i] = glm::uvec2(HMB_NO_SHUTTER_PATH);
    }
    if (i % 4 != 0) list.push_back(i);
  }
  const std::vector<glm::vec4> tiles = mblur::referenceTiles(c.layer, s);
  GatherRun run;
  run.sentinel = glm::vec4(-2.0f);
  const std::vector<glm::vec4> full = runGather(context(), overlaid, tiles, run, s);
  run.mask = &mask;
  run.list = &list;
  run.revealed = &other.layer;
  expectListGather(runGather(context(), c.layer, tiles, run, s), full, list, run.sentinel, "curved overlay");
  PostProcessSettings straight = s;
  straight.motionPath = passes::MotionPath::Linear;
  run.mask = nullptr;
  run.list = nullptr;
  run.revealed = nullptr;
  EXPECT_NE(runGather(context(), overlaid, tiles, run, straight), full) << "the paths should change the gather";
}

// The background gather reads the revealed layer where the mask says HMB_MASK_REVEALED and the
// raster elsewhere: on still layers (the gather copies each pixel) a listed pixel comes out as
// the revealed colour exactly where it is revealed.
TEST_F(HybridCompositeTest, TheBackgroundGatherReadsTheRevealedLayerWhereTheMaskSaysSo) {
  const uint32_t width = 53, height = 31;
  const size_t pixels = size_t(width) * height;
  Layer raster{width, height, std::vector<glm::vec4>(pixels, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f)),
               std::vector<glm::vec4>(pixels, glm::vec4(0, 0, 1, 2)), std::vector<glm::vec2>(pixels, glm::vec2(0.0f))};
  Layer revealed = raster;
  std::vector<uint32_t> mask(pixels, HMB_MASK_NONE), list;
  for (uint32_t i = 0; i < pixels; ++i) {
    revealed.color[i] = glm::vec4(float(i % width), float(i / width), 0.0f, 1.0f);
    if (i % 3 == 0) mask[i] = HMB_MASK_REVEALED;
    else if (i % 3 == 1) mask[i] = HMB_MASK_UNREVEALED;
    if (i % 5 != 0) list.push_back(i);
  }
  const PostProcessSettings s = compositeSettings(8u, 15u, 0u);
  const std::vector<glm::vec4> tiles(passes::tileGridFor(width, height, s.effectiveTileSize()).count(), glm::vec4(0.0f));
  GatherRun run;
  run.mask = &mask;
  run.list = &list;
  run.revealed = &revealed;
  run.sentinel = glm::vec4(-1.0f);
  std::vector<glm::vec4> expected(pixels);
  for (size_t i = 0; i < pixels; ++i) expected[i] = mask[i] == HMB_MASK_REVEALED ? revealed.color[i] : raster.color[i];
  expectListGather(runGather(context(), raster, tiles, run, s), expected, list, run.sentinel, "overlay");
}

// More than 65535 groups of 64: the dispatch folds into two rows, and every listed pixel is
// still written once with its own colour (a still layer: the gather copies the pixel).
TEST_F(HybridCompositeTest, PixelListFoldedIntoTwoRowsOfGroups) {
  const uint32_t width = 2100, height = 2100;
  const size_t pixels = size_t(width) * height;
  Layer layer{width, height, std::vector<glm::vec4>(pixels), std::vector<glm::vec4>(pixels, glm::vec4(0, 0, 1, 1)),
              std::vector<glm::vec2>(pixels, glm::vec2(0.0f))};
  for (size_t i = 0; i < pixels; ++i) layer.color[i] = glm::vec4(float(i % width), float(i / width), 0.5f, 1.0f);
  std::vector<uint32_t> list;
  for (uint32_t i = 0; i < pixels; ++i)
    if (i % 64 != 5) list.push_back(i);
  ASSERT_GT(list.size(), size_t(65535) * 64);
  const PostProcessSettings s = compositeSettings(40u, 15u, 0u);
  const passes::TileGrid grid = passes::tileGridFor(width, height, s.effectiveTileSize());
  const std::vector<glm::vec4> tiles(grid.count(), glm::vec4(0.0f));
  GatherRun run;
  run.sentinel = glm::vec4(-1.0f);
  run.list = &list;
  expectListGather(runGather(context(), layer, tiles, run, s), layer.color, list, run.sentinel, "folded");
}

}  // namespace
}  // namespace hmb::test
