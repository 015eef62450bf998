// The hybrid's shutter rays end to end: each listed pixel's colour is the mean of the sharp
// frames at its strata's times (every (strata / rays)-th stratum centre from its first), the
// other pixels keep the composite's colour, and the report counts what the layer holds.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/frame_plan.h"
#include "hmblur/load_scene.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "runtime/passes/hybrid_stage.h"
#include "tests/reference/render_scene.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using ShutterRaysTest = VulkanTest;

// shutterRays 0: the paper's hybrid; else hybrid-rays with that many strata.
RenderResult renderHybrid(const scene::Scene& scene, uint32_t width, uint32_t height, uint32_t shutterRays,
                          std::optional<uint32_t> rayBudget = std::nullopt) {
  static Renderer renderer(VulkanTest::context());
  RenderSettings settings;
  settings.method = shutterRays == 0 ? Method::Hybrid : Method::HybridRays;
  settings.width = width;
  settings.height = height;
  if (shutterRays != 0) settings.hybrid.shutterRays = shutterRays;
  settings.hybrid.rayBudget = rayBudget;
  return renderer.render(scene, settings);
}

std::vector<float> beauty(const RenderResult& result) { return result.image.find("")->values; }

// Only pixels on a silhouette at some stratum may differ (the rasterizer's tie rule and the ray
// test part there): at most 2% of the listed pixels beyond 1/255, none beyond 0.5.
TEST_F(ShutterRaysTest, ListedPixelsAreTheMeanOfTheSharpFramesAtTheirStrata) {
  constexpr uint32_t kW = 160, kH = 90;
  for (const char* name : {"bistro", "living-room"}) {  // a moving camera; a moving object
    const scene::Scene scene = scene::loadScene(name);
    const RenderResult hybrid = renderHybrid(scene, kW, kH, 8);
    ASSERT_TRUE(hybrid.hybrid && hybrid.plan.runs(passes::HybridStage::kShutterRaysTrace)) << name;
    const uint32_t strata = hybrid.hybrid->settings.shutterRays;
    ASSERT_EQ(strata, 8u);
    const float exposure = hybrid.hybrid->settings.blur.exposure;
    std::vector<std::vector<float>> sharp;
    for (uint32_t s = 0; s < strata; ++s) {
      const float t = hybrid.frameTime - exposure + exposure * (float(s) + 0.5f) / float(strata);
      sharp.push_back(beauty(renderScene(scene, "sharp", 1, 1, t, kW, kH)));
    }
    const io::ImageLayer* rays = hybrid.image.find("shutterRays");
    ASSERT_TRUE(rays) << name;
    const std::vector<float> traced = beauty(hybrid);
    // Without the rays: post-process's gather, and the ray mask's composite, which the rays'
    // frame leaves out (unlisted pixels in that mask may differ).
    const RenderResult paper = renderHybrid(scene, kW, kH, 0);
    const std::vector<float> composite = beauty(paper);
    const std::vector<uint32_t>& mask = paper.image.find("rayMask")->ids;
    size_t listed = 0, raysTraced = 0, off = 0;
    double worst = 0.0;
    for (uint32_t p = 0; p < kW * kH; ++p) {
      const uint32_t n = rays->ids[p];
      if (n == 0) {
        if (mask[p] != 0) continue;
        for (size_t c = 0; c < 4; ++c)
          ASSERT_EQ(traced[p * 4 + c], composite[p * 4 + c]) << name << ": unlisted pixel " << p << " changed";
        continue;
      }
      ASSERT_TRUE(n == 2 || n == 4 || n == 8) << name << ": pixel " << p << " took " << n << " rays";
      ++listed;
      raysTraced += n;
      const uint32_t first = gpu::shutterRayFirstStratum(p, n, strata);
      double d = 0.0;
      for (size_t c = 0; c < 3; ++c) {
        double mean = 0.0;
        for (uint32_t k = 0; k < n; ++k) mean += sharp[first + k * (strata / n)][p * 4 + c] / double(n);
        d = std::max(d, std::abs(double(traced[p * 4 + c]) - mean));
      }
      worst = std::max(worst, d);
      if (d > 1.0 / 255.0) ++off;
    }
    std::cout << "[ shutter rays ] " << name << ": " << listed << " pixels listed, " << raysTraced << " rays; " << off
              << " differ from the mean of the sharp frames by more than 1/255, at most " << worst << "\n";
    EXPECT_GT(listed, size_t(kW) * kH / 100) << name;
    EXPECT_EQ(hybrid.hybrid->shutterRayPixels, listed) << name;
    EXPECT_EQ(hybrid.hybrid->shutterRays, raysTraced) << name;
    EXPECT_LE(off, listed / 50) << name;
    EXPECT_LE(worst, 0.5) << name;
  }
}

// In the paper's method, or on a scene whose meshes deform (the trace scene holds them at the
// frame time only), the plan skips both passes and says why.
TEST_F(ShutterRaysTest, PlanSaysWhyTheyAreSkipped) {
  const RenderResult off = renderHybrid(scene::loadScene("bistro"), 64, 36, 0);
  for (const char* pass : {passes::HybridStage::kShutterRaysList, passes::HybridStage::kShutterRaysTrace}) {
    const auto planned = std::find_if(off.plan.passes().begin(), off.plan.passes().end(),
                                      [&](const PlannedPass& p) { return p.name == pass; });
    ASSERT_NE(planned, off.plan.passes().end()) << pass;
    EXPECT_FALSE(planned->run) << pass;
    EXPECT_EQ(planned->reason, passes::kShutterRaysOffReason);
  }
  EXPECT_EQ(off.hybrid->shutterRayPixels, 0u);
  const io::ImageLayer* rays = off.image.find("shutterRays");
  ASSERT_TRUE(rays);
  EXPECT_TRUE(std::all_of(rays->ids.begin(), rays->ids.end(), [](uint32_t n) { return n == 0u; }));
}

}  // namespace
}  // namespace hmb::test
