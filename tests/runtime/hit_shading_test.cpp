// A user's shading of ray hits (RendererOptions::shadeHit): compiled into the reveal and the
// reference kernels at run time with glslang's library. The library's own shading written
// through the hook renders the frames the built-in kernels do; a different shading changes
// only what rays reveal; a function that does not compile is a one-line error.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/hit_shading.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "tests/support/expect_error.h"
#include "tests/support/spirv_modes.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using HitShadingTest = VulkanTest;

constexpr const char* kLibraryShading =
    "vec3 shadeHit(HitRecord hit) { return shadeSurface(hit.material, hit.uv, hit.normal); }";
// The same, as a user writes it with the installed GLSL include, and the library's miss.
constexpr const char* kLibraryShadingIncluded =
    "#include \"hmblur/hit_shading.glsl\"\n"
    "vec3 shadeHit(HitRecord hit) { return shadeSurface(hit.material, hit.uv, hit.normal); }";
constexpr const char* kLibraryMiss = "vec3 shadeMiss(vec3 direction) { return sceneBackground(); }";
// Every ray that hits nothing sees green, given a unit direction (else dark green).
constexpr const char* kGreenMiss =
    "vec3 shadeMiss(vec3 direction) { return vec3(0.0, abs(length(direction) - 1.0) < 1e-4 ? 1.0 : 0.5, 0.0); }";
// Every revealed surface magenta, whatever it is.
constexpr const char* kMagenta = "vec3 shadeHit(HitRecord hit) { return vec3(1.0, 0.0, 1.0); }";

RenderSettings frameOf(Method method) {
  RenderSettings settings;
  settings.method = method;
  settings.width = 80;
  settings.height = 45;
  settings.reference.samplesPerPixel = 4;
  return settings;
}

const std::vector<float>& beauty(const RenderResult& r) { return r.image.find("")->values; }

TEST_F(HitShadingTest, TheLibrarysShadingThroughTheHookRendersTheBuiltInFrames) {
  const scene::Scene scene = scene::loadScene("temple");  // textured: the texture path runs
  for (const bool byAddress : {false, true}) {
    SCOPED_TRACE(byAddress ? "kernels bound by address" : "plain kernels");
    vk::ContextOptions options;
    options.validation = true;
    options.bindByAddress = byAddress;
    vk::Context context(options);
    Renderer builtIn(context);
    RendererOptions hooked;
    hooked.shadeHit = kLibraryShading;
    Renderer compiled(context, hooked);
    RendererOptions both;  // shadeHit through the installed include, and shadeMiss
    both.shadeHit = kLibraryShadingIncluded;
    both.shadeMiss = kLibraryMiss;
    Renderer compiledBoth(context, both);
    for (const Method method : {Method::Hybrid, Method::HybridRays, Method::Reference}) {
      const RenderResult a = builtIn.render(scene, frameOf(method));
      EXPECT_EQ(beauty(a), beauty(compiled.render(scene, frameOf(method)))) << methodName(method);
      EXPECT_EQ(beauty(a), beauty(compiledBoth.render(scene, frameOf(method)))) << methodName(method) << " with shadeMiss";
    }
    EXPECT_EQ(context.validationErrors(), 0u);
  }
}

TEST_F(HitShadingTest, AnotherShadingChangesOnlyWhatRaysReveal) {
  const scene::Scene scene = scene::loadScene("living-room");
  Renderer builtIn(context());
  RendererOptions magenta;
  magenta.shadeHit = kMagenta;
  Renderer custom(context(), magenta);
  // The paper's hybrid: rays reveal the ray mask (hybrid-rays' shutter rays: below).
  const RenderSettings paper = frameOf(Method::Hybrid);
  const RenderResult a = builtIn.render(scene, paper);
  const RenderResult b = custom.render(scene, paper);
  // The raster's G-buffer is the same: its shading is the library's.
  EXPECT_EQ(a.image.find("depth")->values, b.image.find("depth")->values);
  EXPECT_EQ(a.image.find("objectId")->ids, b.image.find("objectId")->ids);
  const std::vector<uint32_t>& mask = b.image.find("rayMask")->ids;
  ASSERT_EQ(mask, a.image.find("rayMask")->ids);
  // Where rays revealed something, it is magenta; elsewhere the revealed layer is empty.
  const std::vector<float>& revealed = b.image.find("revealed")->values;
  size_t magentaPixels = 0;
  for (size_t i = 0; i < mask.size(); ++i)
    magentaPixels += revealed[3 * i] == 1.0f && revealed[3 * i + 1] == 0.0f && revealed[3 * i + 2] == 1.0f;
  EXPECT_GT(magentaPixels, 10u);
  // The blurred frame changes only within a blur's reach (the tile size) of the ray mask.
  const uint32_t w = b.width, h = b.height, reach = b.postprocess->effectiveTileSize();
  size_t changed = 0, outside = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (std::equal(&beauty(a)[4 * i], &beauty(a)[4 * i + 4], &beauty(b)[4 * i])) continue;
      ++changed;
      bool nearMask = false;
      for (uint32_t yy = y > reach ? y - reach : 0; yy <= std::min(h - 1, y + reach) && !nearMask; ++yy)
        for (uint32_t xx = x > reach ? x - reach : 0; xx <= std::min(w - 1, x + reach) && !nearMask; ++xx)
          nearMask = mask[size_t(yy) * w + xx] != 0;
      outside += !nearMask;
    }
  EXPECT_GT(changed, 10u);
  EXPECT_EQ(outside, 0u) << "of " << changed << " changed pixels";

  // With shutter rays every pixel that took them is the shading's colour (each ray's is
  // magenta), and no other pixel changes.
  const RenderResult c = builtIn.render(scene, frameOf(Method::HybridRays));
  const RenderResult d = custom.render(scene, frameOf(Method::HybridRays));
  const std::vector<uint32_t>& rays = d.image.find("shutterRays")->ids;
  ASSERT_EQ(rays, c.image.find("shutterRays")->ids);
  size_t traced = 0, wrong = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const float* colour = &beauty(d)[4 * i];
    if (rays[i] == 0) {
      wrong += !std::equal(colour, colour + 4, &beauty(c)[4 * i]);
      continue;
    }
    ++traced;
    wrong += !(colour[0] == 1.0f && colour[1] == 0.0f && colour[2] == 1.0f);
  }
  EXPECT_GT(traced, 10u);
  EXPECT_EQ(wrong, 0u) << "of " << rays.size() << " pixels";
}

// A user's shadeMiss is what every ray that hits nothing sees, given its unit direction: the
// reference's pixels whose every sample missed are its colour, and the raster's sky is not.
TEST_F(HitShadingTest, RaysThatHitNothingSeeTheUsersMiss) {
  const scene::Scene scene = scene::loadScene("temple");
  RendererOptions green;
  green.shadeMiss = kGreenMiss;
  Renderer custom(context(), green);
  const RenderResult reference = custom.render(scene, frameOf(Method::Reference));
  const RenderResult sharp = custom.render(scene, frameOf(Method::Sharp));
  const std::vector<uint32_t>& ids = sharp.image.find("objectId")->ids;
  size_t greenPixels = 0, dark = 0, greenInSharp = 0;
  for (size_t i = 0; i < ids.size(); ++i) {
    const float* r = &beauty(reference)[4 * i];
    greenPixels += r[0] == 0.0f && r[1] == 1.0f && r[2] == 0.0f;
    dark += r[0] == 0.0f && r[1] == 0.5f && r[2] == 0.0f;
    const float* s = &beauty(sharp)[4 * i];
    greenInSharp += s[0] == 0.0f && s[1] == 1.0f && s[2] == 0.0f;
  }
  EXPECT_GT(greenPixels, 100u);
  EXPECT_EQ(dark, 0u);          // every direction it was given was unit
  EXPECT_EQ(greenInSharp, 0u);  // the raster keeps the scene's background
  EXPECT_EQ(context().validationErrors(), 0u);
}

// The kernels compiled with a user's shading keep NaN and infinity as the embedded ones do:
// the mode comes with the kernel's own text (kernels/shared/float_controls.glsl).
TEST(HitShadingBuildsTest, KernelsCompiledWithAUsersShadingKeepNanAndInfinity) {
  const passes::HitShading shading(kMagenta);
  for (const char* kernel : {"reveal/reveal_background", "reference/accumulate_sample"}) {
    const vk::KernelBuilds& builds = shading.buildsFor(kernel);
    EXPECT_TRUE(keepsNanAndInfinity(builds.plain)) << kernel;
    if (!builds.byAddress.empty()) {
      EXPECT_TRUE(keepsNanAndInfinity(builds.byAddress)) << kernel << " (address build)";
    }
  }
}

TEST_F(HitShadingTest, AShadeHitThatDoesNotCompileIsAOneLineErrorNamingIt) {
  const scene::Scene scene = scene::loadScene("living-room");
  for (const char* broken : {"vec3 shadeHit(HitRecord hit) { return vec3(1.0) }",   // a missing ';'
                             "vec3 shadeHit(HitRecord hit) { return hit.colour; }",  // no such field
                             "float shadeHit(HitRecord hit) { return 1.0; }"}) {      // the wrong type
    SCOPED_TRACE(broken);
    RendererOptions options;
    options.shadeHit = broken;
    Renderer renderer(context(), options);
    expectError([&] { renderer.render(scene, frameOf(Method::Hybrid)); }, "shadeHit");
  }
  RendererOptions options;
  options.shadeMiss = "vec3 shadeMiss(vec3 direction) { return direction.w; }";  // no such component
  Renderer renderer(context(), options);
  expectError([&] { renderer.render(scene, frameOf(Method::Hybrid)); }, "shadeMiss");
}

}  // namespace
}  // namespace hmb::test
