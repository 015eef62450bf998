#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/image.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "runtime/passes/rasterize_pass.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using RendererTest = VulkanTest;

std::string errorOf(const RenderSettings& settings) {
  try {
    validateRenderSettings(settings);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(RenderSettingsTest, UnknownMethodNamesTheAvailableOnes) {
  std::string message;
  try {
    parseMethod("magic");
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("unknown method 'magic'"), std::string::npos) << message;
  for (const MethodDescription& m : methodDescriptions())
    EXPECT_NE(message.find(std::string(m.name)), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(RenderSettingsTest, EveryMethodIsRegisteredOnceAndNamesRoundTrip) {
  for (const MethodDescription& m : methodDescriptions()) {
    EXPECT_EQ(parseMethod(m.name), m.method) << m.name;
    EXPECT_EQ(methodName(m.method), m.name);
    EXPECT_EQ(&describe(m.method), &m) << m.name << " is registered twice";
    EXPECT_NE(m.make, nullptr) << m.name;
    EXPECT_NE(m.validate, nullptr) << m.name;
  }
  EXPECT_EQ(methodNames(), (std::vector<std::string>{"sharp", "postprocess", "hybrid", "hybrid-rays", "reference"}));
}

TEST(RenderSettingsTest, EmptyAndAbsurdSizesAreRejected) {
  RenderSettings settings;
  settings.width = 0;
  EXPECT_NE(errorOf(settings).find("empty"), std::string::npos);
  settings.width = kMaxImageSide + 1;
  EXPECT_NE(errorOf(settings).find("exceeds"), std::string::npos);
  settings.width = 7;
  settings.height = 3;
  EXPECT_EQ(errorOf(settings), "");
  settings.frameTime = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(errorOf(settings).find("finite"), std::string::npos);
}

TEST_F(RendererTest, TestPatternFrameHasBeautyDisplayAndPlan) {
  Renderer renderer(context());
  const scene::Scene empty;
  RenderSettings settings;
  settings.method = Method::TestPattern;
  settings.width = 7;
  settings.height = 3;
  const RenderResult result = renderer.render(empty, settings);
  ASSERT_EQ(result.image.width, 7u);
  ASSERT_EQ(result.image.height, 3u);
  const io::ImageLayer* beauty = result.image.find("");
  ASSERT_NE(beauty, nullptr);
  ASSERT_EQ(beauty->values.size(), 7u * 3u * 4u);

  // The display image is the display transform of the beauty layer.
  std::vector<glm::vec4> linear;
  for (size_t i = 0; i < beauty->values.size(); i += 4)
    linear.emplace_back(beauty->values[i], beauty->values[i + 1], beauty->values[i + 2], beauty->values[i + 3]);
  const io::Rgba8Image expected = io::encodeDisplay(7, 3, linear);
  ASSERT_EQ(result.display.pixels.size(), expected.pixels.size());
  for (size_t i = 0; i < expected.pixels.size(); ++i)
    EXPECT_LE(std::abs(int(result.display.pixels[i]) - int(expected.pixels[i])), 1) << i;

  for (const auto& pass : result.plan.passes()) {
    EXPECT_TRUE(pass.run) << pass.name;
    if (context().info().timestamps) {
      EXPECT_TRUE(pass.milliseconds.has_value()) << pass.name;
    }
  }
  EXPECT_TRUE(result.plan.runs("test-pattern"));
  EXPECT_TRUE(result.plan.runs("encode-display"));
}

TEST_F(RendererTest, ImageLargerThanTheDeviceAllowsFailsBeforeRendering) {
  Renderer renderer(context());
  RenderSettings settings;
  // 16384^2 RGBA float is 4 GiB: beyond any single storage buffer of a 32-bit range.
  settings.width = kMaxImageSide;
  settings.height = kMaxImageSide;
  if (uint64_t(kMaxImageSide) * kMaxImageSide * 16 <= context().limits().maxStorageBufferRange)
    GTEST_SKIP() << "this device takes the largest image";
  EXPECT_THROW(renderer.render(scene::Scene{}, settings), Error);
}

// The sharp method: beauty plus the AOV layers every later method reads, and a plan that names
// every G-buffer pass with its time.
TEST_F(RendererTest, SharpFrameHasBeautyAovsPlanAndRasterStats) {
  Renderer renderer(context());
  const scene::Scene scene = scene::loadScene("living-room");
  RenderSettings settings;
  settings.method = Method::Sharp;
  settings.width = 67;
  settings.height = 37;
  const RenderResult result = renderer.render(scene, settings);
  const size_t pixels = 67 * 37;
  const std::pair<const char*, size_t> layers[] = {{"", 4}, {"depth", 1}, {"normal", 3}, {"velocity", 2}};
  for (const auto& [name, channels] : layers) {
    const io::ImageLayer* layer = result.image.find(name);
    ASSERT_NE(layer, nullptr) << name;
    ASSERT_EQ(layer->values.size(), pixels * channels) << name;
    for (float v : layer->values) ASSERT_TRUE(std::isfinite(v)) << name;
  }
  const io::ImageLayer* ids = result.image.find("objectId");
  ASSERT_NE(ids, nullptr);
  ASSERT_TRUE(ids->isUint);
  ASSERT_EQ(ids->ids.size(), pixels);
  EXPECT_GT(std::count_if(ids->ids.begin(), ids->ids.end(), [](uint32_t id) { return id != 0; }), 0);

  EXPECT_EQ(result.visibilityScheme, passes::visibilitySchemeName(passes::defaultVisibilityScheme(context())));
  EXPECT_GT(result.raster.setupTriangles, 0u);
  EXPECT_GT(result.raster.tilePairs, 0u);
  for (const char* pass : {"transform-vertices", "setup-triangles", "bin-large-triangles", "resolve-gbuffer",
                           "encode-display"})
    EXPECT_TRUE(result.plan.runs(pass)) << pass;
  if (context().info().timestamps) {
    for (const auto& pass : result.plan.passes()) {
      if (pass.run && pass.within.empty()) {  // a path inside other passes has no time of its own
        EXPECT_TRUE(pass.milliseconds.has_value()) << pass.name;
      }
    }
  }
}

// A device without 64-bit buffer atomics gets the two-pass visibility, the plan says so, and
// the picture is the same.
// A validating context that pretends the device has no 64-bit buffer atomics.
vk::ContextOptions withoutInt64Atomics() {
  vk::ContextOptions options;
  options.validation = true;
  options.disableInt64Atomics = true;
  return options;
}

TEST_F(RendererTest, DeviceWithoutInt64AtomicsRendersTheSameFrameWithTheFallback) {
  vk::Context fallbackContext(withoutInt64Atomics());
  const scene::Scene scene = scene::loadScene("temple");
  RenderSettings settings;
  settings.width = 80;
  settings.height = 45;
  Renderer fallback(fallbackContext, {passes::VisibilityScheme::Depth32TwoPass});
  const RenderResult a = fallback.render(scene, settings);
  EXPECT_EQ(fallbackContext.validationErrors(), 0u);
  EXPECT_EQ(a.visibilityScheme, "depth32-two-pass");
  EXPECT_TRUE(a.plan.runs("rasterize-depth32"));
  EXPECT_TRUE(a.plan.runs("rasterize-ids32"));
  EXPECT_FALSE(a.plan.runs("rasterize-tiles"));
  const auto skipped = std::find_if(a.plan.passes().begin(), a.plan.passes().end(),
                                    [](const PlannedPass& p) { return p.name == "rasterize-tiles"; });
  ASSERT_NE(skipped, a.plan.passes().end());
  EXPECT_NE(skipped->reason.find("shaderBufferInt64Atomics"), std::string::npos) << skipped->reason;

  Renderer native(context(), {passes::VisibilityScheme::Int64Atomics});
  const RenderResult b = native.render(scene, settings);
  EXPECT_EQ(b.visibilityScheme, "int64-atomics");
  EXPECT_EQ(a.display.pixels, b.display.pixels);
  EXPECT_EQ(a.image.find("objectId")->ids, b.image.find("objectId")->ids);
}

// A CPU device rasterizes with per-tile lists (no atomics, no 64-bit types); the frame is the
// one the atomic scheme renders, byte for byte, also on a device without 64-bit atomics.
TEST_F(RendererTest, CpuDevicesRasterizeWithTileListsAndRenderTheSameFrame) {
  const scene::Scene scene = scene::loadScene("living-room");
  RenderSettings settings;
  settings.method = Method::PostProcess;
  settings.width = 96;
  settings.height = 52;  // tiles cut by the right and bottom edges
  vk::Context without64(withoutInt64Atomics());
  Renderer lists(without64, {passes::VisibilityScheme::TileLists});
  const RenderResult a = lists.render(scene, settings);
  EXPECT_EQ(without64.validationErrors(), 0u);
  EXPECT_EQ(a.visibilityScheme, "tile-lists");
  EXPECT_TRUE(a.plan.runs("link-tile-pairs"));
  EXPECT_TRUE(a.plan.runs("rasterize-tile-lists"));
  EXPECT_FALSE(a.plan.runs("clear-visibility"));
  if (context().profile().rasterTileLists) {
    Renderer byDefault(context());
    EXPECT_EQ(byDefault.render(scene, settings).visibilityScheme, "tile-lists");
  }
  Renderer atomics(context(), {passes::VisibilityScheme::Int64Atomics});
  const RenderResult b = atomics.render(scene, settings);
  EXPECT_EQ(a.display.pixels, b.display.pixels);
  EXPECT_EQ(a.image.find("objectId")->ids, b.image.find("objectId")->ids);
}

// Time slices: the shutter cut into K slices, each the method's frame over its own slice (as
// if the scene's exposure were E / K, closing K - 1 - k slices before the frame time, gather
// seed k; the hybrid's falling foreground boost k / K, the whole shutter's), and the frame their
// mean; its time is the slices' sum. One slice is the frame without slices.
TEST_F(RendererTest, TimeSlicesAreTheMeanOfTheirSlicesFrames) {
  const scene::Scene scene = scene::loadScene("living-room");
  Renderer renderer(context());
  for (const Method method : {Method::PostProcess, Method::Hybrid}) {
    RenderSettings settings;
    settings.method = method;
    settings.width = 64;
    settings.height = 36;
    const RenderResult whole = renderer.render(scene, settings);
    settings.postprocess.timeSlices = 1;
    EXPECT_EQ(renderer.render(scene, settings).display.pixels, whole.display.pixels);

    constexpr uint32_t kSlices = 3;
    settings.postprocess.timeSlices = kSlices;
    const RenderResult sliced = renderer.render(scene, settings);
    scene::Scene slice = scene;
    slice.settings.exposure = scene.settings.exposure / float(kSlices);
    RenderSettings one = settings;
    one.postprocess.timeSlices.reset();
    if (method == Method::Hybrid)
      one.postprocess.foregroundBoostPixels = passes::kHybridForegroundBoostPixels / float(kSlices);
    std::vector<glm::vec4> sum(size_t(64) * 36, glm::vec4(0.0f));
    for (uint32_t k = 0; k < kSlices; ++k) {
      one.frameTime = scene.settings.frameTime - float(kSlices - 1 - k) * slice.settings.exposure;
      one.postprocess.seed = k;
      const RenderResult r = renderer.render(slice, one);
      const std::vector<float>& beauty = r.image.find("")->values;
      for (size_t i = 0; i < sum.size(); ++i)
        sum[i] += glm::vec4(beauty[4 * i], beauty[4 * i + 1], beauty[4 * i + 2], beauty[4 * i + 3]);
    }
    for (glm::vec4& v : sum) v /= float(kSlices);
    const std::vector<float>& beauty = sliced.image.find("")->values;
    for (size_t i = 0; i < sum.size(); ++i)
      for (int c = 0; c < 4; ++c) ASSERT_EQ(beauty[4 * i + c], sum[i][c]) << "pixel " << i;
    EXPECT_EQ(sliced.display.pixels, io::encodeDisplay(64, 36, sum).pixels);
    EXPECT_NE(sliced.display.pixels, whole.display.pixels);
    EXPECT_EQ(sliced.frameTime, scene.settings.frameTime);
    // Whether the frame's time spans its slices is a benchmark's question (timings vary with
    // the machine's load); the test asks only that a time is reported where one was before.
    EXPECT_EQ(sliced.frameMilliseconds.has_value(), whole.frameMilliseconds.has_value());
    ASSERT_TRUE(sliced.postprocess);
    EXPECT_EQ(sliced.postprocess->timeSlices, kSlices);
    EXPECT_EQ(sliced.postprocess->exposure, scene.settings.exposure / float(kSlices));  // a slice's
  }
  EXPECT_EQ(context().validationErrors(), 0u);
}

// The hybrid's image is the post-process gather's outside the shutter rays' pixels, bit for
// bit (with the rays the mask is left out); without the rays, outside the ray mask: its
// composite rewrites the mask's pixels alone. Both paths, on a scene whose mask is not empty;
// post-process with the hybrid's foreground boost (the two methods' defaults differ).
TEST_F(RendererTest, TheHybridEqualsPostProcessOutsideItsRayMask) {
  const scene::Scene scene = scene::loadScene("living-room");
  Renderer renderer(context());
  for (const passes::MotionPath path : {passes::MotionPath::Linear, passes::MotionPath::Curved}) {
    RenderSettings settings;
    settings.width = 96;
    settings.height = 54;
    settings.postprocess.motionPath = path;
    settings.method = Method::HybridRays;
    const RenderResult hybrid = renderer.render(scene, settings);
    settings.method = Method::Hybrid;  // the paper's: ray mask, reveal, composite
    const RenderResult composited = renderer.render(scene, settings);
    ASSERT_TRUE(hybrid.hybrid && composited.hybrid);
    settings.method = Method::PostProcess;
    settings.postprocess.foregroundBoostPixels = hybrid.hybrid->settings.blur.foregroundBoostPixels;
    const RenderResult post = renderer.render(scene, settings);
    ASSERT_TRUE(post.postprocess);
    EXPECT_EQ(*post.postprocess, hybrid.hybrid->settings.blur);
    const std::vector<float>& a = post.image.find("")->values;
    const std::vector<uint32_t>& mask = composited.image.find("rayMask")->ids;
    const std::vector<uint32_t>& rays = hybrid.image.find("shutterRays")->ids;
    ASSERT_EQ(mask.size() * 4, a.size());
    ASSERT_EQ(rays.size(), mask.size());
    EXPECT_EQ(hybrid.image.find("rayMask")->ids, std::vector<uint32_t>(mask.size(), 0u)) << "the mask beside the rays";
    // in[0]: the mask's pixels, in[1]: the shutter rays'; changed[k]: those that differ from
    // post-process, without shutter rays and with.
    size_t in[2] = {}, changed[2] = {};
    for (size_t i = 0; i < mask.size(); ++i) {
      for (int k = 0; k < 2; ++k) {
        const std::vector<float>& b = (k == 0 ? composited : hybrid).image.find("")->values;
        ASSERT_EQ(a.size(), b.size());
        const bool same = std::equal(a.begin() + 4 * i, a.begin() + 4 * i + 4, b.begin() + 4 * i);
        const bool inside = k == 0 ? mask[i] != 0u : rays[i] != 0u;
        if (inside) {
          ++in[k];
          changed[k] += !same;
        } else {
          EXPECT_TRUE(same) << "pixel " << i << (k == 0 ? " outside the mask" : " outside the shutter rays");
        }
      }
    }
    EXPECT_GT(in[0], 20u);
    EXPECT_GT(changed[0], in[0] / 2) << "the composite changes the mask's pixels";
    EXPECT_GT(in[1], 20u);
    EXPECT_GT(changed[1], in[1] / 2) << "the shutter rays change theirs";
  }
  EXPECT_EQ(context().validationErrors(), 0u);
}

TEST(RenderSettingsTest, TimeSlicesBelongToTheBlursAndAreBounded) {
  RenderSettings settings;
  settings.method = Method::PostProcess;
  settings.postprocess.timeSlices = 0;
  EXPECT_NE(errorOf(settings).find("time-slices"), std::string::npos) << errorOf(settings);
  settings.postprocess.timeSlices = passes::kMaxTimeSlices + 1;
  EXPECT_NE(errorOf(settings).find("time-slices"), std::string::npos) << errorOf(settings);
  settings.postprocess.timeSlices = 4;
  EXPECT_EQ(errorOf(settings), "");
  settings.method = Method::Hybrid;
  EXPECT_EQ(errorOf(settings), "");
}

}  // namespace
}  // namespace hmb::test
