// The reference renderer (kernels/reference/, runtime/passes/reference_stage): what it must
// agree with (the sharp raster image of the same instant), how it converges, and that a
// checkpointed render resumes to the same image.
#include <bit>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "runtime/metrics/display_image.h"
#include "runtime/metrics/metrics.h"
#include "runtime/passes/reference_stage.h"
#include "tests/reference/render_scene.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;
using ReferenceTest = VulkanTest;

constexpr uint32_t kWidth = 96, kHeight = 54;

RenderResult renderWith(const scene::Scene& scene, const std::string& method, uint32_t spp, uint32_t seed = 1,
                        std::optional<float> frameTime = std::nullopt, uint32_t width = kWidth,
                        uint32_t height = kHeight) {
  return renderScene(scene, method, spp, seed, frameTime, width, height);
}

double displayMse(const io::Rgba8Image& a, const io::Rgba8Image& b) {
  return metrics::meanSquaredError(metrics::displayImageFromRgba8(a), metrics::displayImageFromRgba8(b));
}

double psnr(double mse) { return metrics::psnrFromMse(mse); }

scene::Scene staticCopy(scene::Scene scene) {
  scene.channels.clear();
  return scene;
}

// Without motion every shutter time sees the same instant: the reference is the raster image.
// They may differ only where a pixel centre lies exactly on a silhouette edge (the rasterizer's
// top-left rule and the watertight ray test break that tie differently): at 512x288 one such
// pixel costs about 10 dB of a perfect match; at 512x288 bistro has 18 such pixels (52 dB).
TEST_F(ReferenceTest, StaticSceneEqualsTheSharpRasterImage) {
  for (const char* name : {"living-room", "temple", "bistro"}) {
    const scene::Scene scene = staticCopy(scene::loadScene(name));
    const RenderResult sharp = renderWith(scene, "sharp", 1, 1, std::nullopt, 512, 288);
    const RenderResult reference = renderWith(scene, "reference", 4, 1, std::nullopt, 512, 288);
    const double db = psnr(displayMse(sharp.display, reference.display));
    EXPECT_GT(db, 50.0) << name;
    std::cout << "[ static   ] " << name << ": reference vs sharp " << db << " dB\n";
  }
}

// One sample is one instant: the raster image at that sample's shutter time, moving camera
// and rotating objects included.
TEST_F(ReferenceTest, OneSampleEqualsTheRasterImageAtItsShutterTime) {
  for (const char* name : {"living-room", "bistro"}) {
    const scene::Scene scene = scene::loadScene(name);
    const uint32_t seed = 7;
    const float t = passes::referenceShutterTimes(scene.settings.frameTime, scene.settings.exposure, 1, seed)[0];
    const RenderResult sharp = renderWith(scene, "sharp", 1, seed, t, 512, 288);
    const RenderResult reference = renderWith(scene, "reference", 1, seed, std::nullopt, 512, 288);
    const double db = psnr(displayMse(sharp.display, reference.display));
    EXPECT_GT(db, 50.0) << name << " at t = " << t;
    std::cout << "[ instant  ] " << name << " at t = " << t << ": reference vs sharp " << db << " dB\n";
  }
}

TEST(ReferenceShutterTimes, EveryStratumOnceInsideTheShutter) {
  for (const uint32_t n : {1u, 2u, 3u, 10u, 64u, 1000u, 1024u}) {
    const std::vector<float> times = passes::referenceShutterTimes(2.0f, 0.5f, n, 3);
    ASSERT_EQ(times.size(), n);
    std::vector<int> hits(n, 0);
    for (const float t : times) {
      ASSERT_GE(t, 1.5f);
      ASSERT_LE(t, 2.0f);
      const auto stratum = std::min<uint32_t>(n - 1, static_cast<uint32_t>((t - 1.5f) / 0.5f * float(n)));
      ++hits[stratum];
    }
    for (uint32_t s = 0; s < n; ++s) EXPECT_EQ(hits[s], 1) << "stratum " << s << " of " << n;
    // Any prefix spreads over the shutter: the first quarter of the samples reaches both halves.
    if (n >= 8) {
      bool early = false, late = false;
      for (uint32_t k = 0; k < n / 4; ++k) (times[k] < 1.75f ? early : late) = true;
      EXPECT_TRUE(early && late) << n;
    }
  }
}

// Error against a 1024-spp reference (another seed) falls as samples grow: at least as fast
// as 1/N^(1/2) in MSE per fourfold samples, once the strata are finer than the motion.
TEST_F(ReferenceTest, ErrorFallsAsSamplesGrow) {
  const scene::Scene scene = scene::loadScene("living-room");
  const RenderResult judge = renderWith(scene, "reference", 1024, 99);
  std::vector<double> mse;
  for (const uint32_t spp : {4u, 16u, 64u, 256u}) {
    mse.push_back(displayMse(judge.display, renderWith(scene, "reference", spp, 5).display));
    std::cout << "[ converge ] " << spp << " spp: MSE " << mse.back() << " (" << psnr(mse.back()) << " dB)\n";
  }
  for (size_t i = 1; i < mse.size(); ++i) EXPECT_LT(mse[i], mse[i - 1] / 2.0) << "step " << i;
}

// With a still camera, pixels that nothing moving crosses take one sample: the image is the
// one every pixel sampled at every time gives (up to rounding), at a fraction of the rays.
TEST_F(ReferenceTest, StillPixelsSampledOnceGiveTheSameImage) {
  const scene::Scene scene = scene::loadScene("temple");
  Renderer renderer(context());
  RenderSettings settings;
  settings.method = Method::Reference;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.reference.samplesPerPixel = 16;
  const RenderResult once = renderer.render(scene, settings);
  settings.reference.sampleStillPixelsOnce = false;
  const RenderResult every = renderer.render(scene, settings);
  ASSERT_TRUE(once.reference && once.reference->movingPixels);
  EXPECT_FALSE(every.reference->movingPixels.has_value());
  EXPECT_GT(*once.reference->movingPixels, 0u);
  EXPECT_LT(*once.reference->movingPixels, uint64_t(kWidth) * kHeight);
  EXPECT_GT(psnr(displayMse(once.display, every.display)), 60.0);
  std::cout << "[ still    ] temple: " << *once.reference->movingPixels << " of " << kWidth * kHeight
            << " pixels take every sample\n";
  // A moving camera needs every pixel every time.
  settings.reference.sampleStillPixelsOnce = true;
  const RenderResult bistro = renderer.render(scene::loadScene("bistro"), settings);
  EXPECT_FALSE(bistro.reference->movingPixels.has_value());
}

TEST_F(ReferenceTest, CheckpointResumesToTheSameImage) {
  const scene::Scene scene = scene::loadScene("living-room");
  const fs::path checkpoint = fs::path(testing::TempDir()) / "hmb_reference_checkpoint.bin";
  fs::remove(checkpoint);
  Renderer renderer(context());
  RenderSettings settings;
  settings.method = Method::Reference;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.reference.samplesPerPixel = 12;
  settings.reference.timesPerBatch = 4;
  const RenderResult whole = renderer.render(scene, settings);

  // Stopped during the third batch: the checkpoint holds the first two batches.
  settings.reference.checkpoint = checkpoint;
  settings.onProgress = [](const passes::ReferenceProgress& p) {
    if (p.samplesDone == 10) throw std::runtime_error("stopped");
  };
  EXPECT_THROW(renderer.render(scene, settings), std::runtime_error);
  ASSERT_TRUE(fs::exists(checkpoint));

  uint32_t rendered = 0;
  settings.onProgress = [&](const passes::ReferenceProgress&) { ++rendered; };
  const RenderResult resumed = renderer.render(scene, settings);
  ASSERT_TRUE(resumed.reference.has_value());
  EXPECT_EQ(resumed.reference->samplesResumed, 8u);
  EXPECT_EQ(resumed.reference->samplesDone, 12u);
  EXPECT_EQ(rendered, 4u);
  EXPECT_EQ(resumed.image.layers[0].values, whole.image.layers[0].values);

  // A finished checkpoint renders nothing more; other settings refuse it in one line.
  rendered = 0;
  renderer.render(scene, settings);
  EXPECT_EQ(rendered, 0u);
  settings.reference.seed = 2;
  try {
    renderer.render(scene, settings);
    ADD_FAILURE() << "a checkpoint of other settings was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("other settings"), std::string::npos) << e.what();
  }
  fs::remove(checkpoint);
}

// One scene at 160x90 rendered by the judge (128 spp, another seed than the methods' own
// randomness) and by the sharp frame, cached for the claims below.
struct JudgedScene {
  scene::Scene scene;
  metrics::DisplayImage judge;
  metrics::DisplayImage sharp;
  metrics::BlurRegion region;
};

// The size and the judge's samples the claims are made at (the image-quality issue's: 320x180
// against a 256-spp reference).
constexpr uint32_t kClaimWidth = 320, kClaimHeight = 180, kJudgeSpp = 256;

metrics::DisplayImage displayOf(const RenderResult& r) { return metrics::displayImageFromRgba8(r.display); }

// make: the scene named `name` when given (one made here), else the reference scene.
const JudgedScene& judged(const std::string& name, const std::function<scene::Scene()>& make = {}) {
  static std::map<std::string, JudgedScene> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  JudgedScene j;
  j.scene = make ? make() : scene::loadScene(name);
  j.judge = displayOf(renderWith(j.scene, "reference", kJudgeSpp, 11, std::nullopt, kClaimWidth, kClaimHeight));
  j.sharp = displayOf(renderWith(j.scene, "sharp", 1, 1, std::nullopt, kClaimWidth, kClaimHeight));
  j.region = metrics::blurRegion(j.judge, j.sharp);
  return cache.emplace(name, std::move(j)).first->second;
}

// The baseline's claim, against the judge: on every reference scene, post-process blur
// (adapted range, the paper's settings) is closer to the reference than the sharp frame over
// the blur region. Not claimed over the whole frame: screen velocity is linear, so a ring
// spinning in its own plane (the temple's sun wheel, unchanged to the reference) is smeared
// along its tangents, and those pixels outweigh the gain elsewhere in some scenes.
TEST_F(ReferenceTest, PostProcessIsCloserToTheReferenceThanTheSharpFrame) {
  for (const char* name : {"living-room", "temple", "bistro"}) {
    const JudgedScene& j = judged(name);
    const metrics::DisplayImage blurred =
        displayOf(renderWith(j.scene, "postprocess", 1, 1, std::nullopt, kClaimWidth, kClaimHeight));
    ASSERT_GT(j.region.pixelCount, 0u) << name;
    const metrics::Comparison sharpError = metrics::compareImages(j.judge, j.sharp, &j.region);
    const metrics::Comparison blurError = metrics::compareImages(j.judge, blurred, &j.region);
    EXPECT_GT(blurError.region->psnr, sharpError.region->psnr) << name;
    EXPECT_LT(blurError.region->flip, sharpError.region->flip) << name;
    std::cout << "[ baseline ] " << name << ": blur region (" << j.region.pixelCount << " px) PSNR sharp "
              << sharpError.region->psnr << " dB, post-process " << blurError.region->psnr << " dB; frame "
              << sharpError.frame.psnr << " dB, " << blurError.frame.psnr << " dB\n";
  }
}

// A method's error against a scene's judge at the claims' size; `configure` sets its settings.
metrics::Comparison claimError(const JudgedScene& j, Method method,
                               const std::function<void(RenderSettings&)>& configure = {},
                               RenderResult* result = nullptr) {
  RenderSettings settings;
  settings.method = method;
  settings.width = kClaimWidth;
  settings.height = kClaimHeight;
  if (configure) configure(settings);
  static Renderer renderer(VulkanTest::context());
  RenderResult rendered = renderer.render(j.scene, settings);
  const metrics::Comparison c = metrics::compareImages(j.judge, displayOf(rendered), &j.region);
  if (result) *result = std::move(rendered);
  return c;
}

// The paper's claim (section 5.1, Table 1: 25.69 vs 24.20 dB, SSIM 0.92 vs 0.91), on the
// paper's method (its steps 1-5 with this project's defaults: coverage composite, foreground
// boost 80 / |v_N|): the hybrid is closer to the reference than adapted post-process (the
// paper's settings, boost 30) over the blur region by the image-quality issue's margin, 1.5 dB,
// and no worse over the whole frame, on the living room and temple. On bistro, whose blur is
// mostly the camera's and whose edges mostly have nothing deeper behind them to reveal, the
// paper's method gained 1.04 dB at this size when this test was written: it must keep that gain
// less kBistroMarginDb, a margin stated here once. The paper's reveal stop and foreground boost,
// and the weights composite, are printed beside it.
TEST_F(ReferenceTest, HybridIsCloserToTheReferenceThanAdaptedPostProcess) {
  constexpr double kBistroGainDb = 1.04, kBistroMarginDb = 0.5;
  struct Claim {
    const char* scene;
    double regionGainDb;
  };
  for (const Claim claim :
       {Claim{"living-room", 1.5}, Claim{"temple", 1.5}, Claim{"bistro", kBistroGainDb - kBistroMarginDb}}) {
    const JudgedScene& j = judged(claim.scene);
    const metrics::Comparison post = claimError(j, Method::PostProcess);
    const metrics::Comparison hybrid = claimError(j, Method::Hybrid);
    const metrics::Comparison weights = claimError(j, Method::Hybrid, [](RenderSettings& s) {
      s.hybrid.composite = passes::HybridComposite::Weights;
    });
    const metrics::Comparison luminance = claimError(j, Method::Hybrid, [](RenderSettings& s) {
      s.hybrid.stop = passes::RevealStop::Luminance;
    });
    const metrics::Comparison paperBoost =
        claimError(j, Method::Hybrid, [](RenderSettings& s) { s.postprocess.foregroundBoost = 30.0f; });
    ASSERT_TRUE(post.region && hybrid.region && weights.region && luminance.region && paperBoost.region)
        << claim.scene;
    ASSERT_TRUE(post.frame.ssim && hybrid.frame.ssim) << claim.scene;
    EXPECT_GT(hybrid.region->psnr, post.region->psnr + claim.regionGainDb) << claim.scene;
    EXPECT_GE(hybrid.frame.psnr, post.frame.psnr) << claim.scene;
    std::cout << "[ hybrid ] " << claim.scene << ": blur region (" << j.region.pixelCount
              << " px) PSNR post-process " << post.region->psnr << " dB, hybrid " << hybrid.region->psnr
              << " dB (weights composite " << weights.region->psnr << " dB, luminance stop " << luminance.region->psnr
              << " dB, boost 30 " << paperBoost.region->psnr << " dB); frame " << post.frame.psnr << " / "
              << hybrid.frame.psnr << " dB; SSIM " << *post.frame.ssim << " / " << *hybrid.frame.ssim << "\n";
  }
}

// The extension's claim: hybrid-rays (shutter rays over 8 strata where a path crosses an edge)
// is closer to the reference than adapted post-process over the blur region by the same 1.5 dB
// on every scene, bistro's camera blur included, and over the whole frame and in SSIM.
TEST_F(ReferenceTest, HybridRaysIsCloserToTheReferenceThanAdaptedPostProcessOnEveryScene) {
  for (const char* name : {"living-room", "temple", "bistro"}) {
    const JudgedScene& j = judged(name);
    const metrics::Comparison post = claimError(j, Method::PostProcess);
    const metrics::Comparison rays = claimError(j, Method::HybridRays);
    ASSERT_TRUE(post.region && rays.region && post.frame.ssim && rays.frame.ssim && post.region->ssim &&
                rays.region->ssim)
        << name;
    EXPECT_GT(rays.region->psnr, post.region->psnr + 1.5) << name;
    EXPECT_GE(rays.frame.psnr, post.frame.psnr) << name;
    EXPECT_GT(*rays.frame.ssim, *post.frame.ssim) << name;
    EXPECT_GT(*rays.region->ssim, *post.region->ssim) << name;
    std::cout << "[ hybrid-rays ] " << name << ": blur region PSNR post-process " << post.region->psnr
              << " dB, hybrid-rays " << rays.region->psnr << " dB; frame " << post.frame.psnr << " / "
              << rays.frame.psnr << " dB; SSIM " << *post.frame.ssim << " / " << *rays.frame.ssim << "\n";
  }
}

// A ray budget spends rays where they remove the most error: given as many rays as the paper's
// method traced in its reveal on the same frame, hybrid-rays traces at most that many and is at
// least as close to the reference over the blur region as the paper's method.
TEST_F(ReferenceTest, AtThePapersRayCountHybridRaysIsAtLeastAsClose) {
  for (const char* name : {"living-room", "temple", "bistro"}) {
    const JudgedScene& j = judged(name);
    RenderResult paper, budgeted;
    const metrics::Comparison paperError = claimError(j, Method::Hybrid, {}, &paper);
    ASSERT_TRUE(paper.hybrid && paper.hybrid->revealRays > 0) << name;
    const uint32_t budget = uint32_t(paper.hybrid->revealRays);
    const metrics::Comparison raysError =
        claimError(j, Method::HybridRays, [&](RenderSettings& s) { s.hybrid.rayBudget = budget; }, &budgeted);
    ASSERT_TRUE(paperError.region && raysError.region && budgeted.hybrid) << name;
    EXPECT_LE(budgeted.hybrid->shutterRays, budget) << name;
    EXPECT_GE(raysError.region->psnr, paperError.region->psnr) << name;
    std::cout << "[ budget ] " << name << ": " << budget << " rays (the paper's reveal): hybrid "
              << paperError.region->psnr << " dB, hybrid-rays " << raysError.region->psnr << " dB over the blur region ("
              << budgeted.hybrid->shutterRays << " rays at " << budgeted.hybrid->shutterRayPixelsTraced << " of "
              << budgeted.hybrid->shutterRayPixels << " listed pixels)\n";
  }
}

// Time slices buy quality in steps (issue: fill the error-vs-time front between hybrid and a
// few-spp reference): on every reference scene, post-process and both hybrids with the shutter
// cut into 2 slices are closer to the reference over the blur region than with one, by the same
// margin everywhere, and 4 slices closer than 2.
TEST_F(ReferenceTest, TimeSlicesBringEachBlurCloserToTheReference) {
  constexpr double kMarginDb = 1.5;
  for (const char* name : {"living-room", "temple", "bistro"}) {
    const JudgedScene& j = judged(name);
    for (const char* method : {"postprocess", "hybrid", "hybrid-rays"}) {
      double psnr[3] = {};
      for (const uint32_t slices : {1u, 2u, 4u}) {
        RenderSettings settings;
        settings.method = parseMethod(method);
        settings.width = kClaimWidth;
        settings.height = kClaimHeight;
        settings.postprocess.timeSlices = slices;
        static Renderer renderer(VulkanTest::context());
        const metrics::Comparison c =
            metrics::compareImages(j.judge, displayOf(renderer.render(j.scene, settings)), &j.region);
        ASSERT_TRUE(c.region) << name;
        psnr[std::bit_width(slices) - 1] = c.region->psnr;
      }
      EXPECT_GT(psnr[1], psnr[0] + kMarginDb) << name << " " << method;
      EXPECT_GT(psnr[2], psnr[1]) << name << " " << method;
      std::cout << "[ slices ] " << name << " " << method << ": blur region PSNR " << psnr[0] << " / " << psnr[1]
                << " / " << psnr[2] << " dB with 1 / 2 / 4 time slices\n";
    }
  }
}

// The living room with the camera riding along with the vase: the vase stands still on screen
// and the room sweeps behind it, the case the hybrid's ray mask was not built for (it looks
// for moving objects in front of a deeper background). Neither hybrid may be worse than adapted
// post-process there, over the blur region or the frame.
scene::Scene livingRoomRidingWithTheVase() {
  scene::Scene scene = scene::loadScene("living-room");
  const int32_t cameraNode = scene.camera.value().node;
  const scene::AnimationChannel* vase = nullptr;
  for (const scene::AnimationChannel& c : scene.channels)
    if (c.path == scene::AnimationPath::Translation && scene.nodes[c.node].name == "vase") vase = &c;
  if (!vase || cameraNode < 0 || scene.nodes[size_t(cameraNode)].parent >= 0)
    throw Error("the living room's vase channel or root camera node is missing");
  scene::AnimationChannel ride = *vase;
  ride.node = static_cast<uint32_t>(cameraNode);
  const glm::vec3 rest = scene.nodes[size_t(cameraNode)].local.translation;
  const glm::vec3 vaseAtFrame = glm::vec3(vase->values[1]);
  for (glm::vec4& key : ride.values) key = glm::vec4(rest + glm::vec3(key) - vaseAtFrame, 0.0f);
  scene.channels.push_back(ride);
  return scene;
}

TEST_F(ReferenceTest, WithTheCameraRidingAlongHybridIsNoWorseThanPostProcess) {
  const JudgedScene& j = judged("living-room riding with the vase", livingRoomRidingWithTheVase);
  ASSERT_GT(j.region.pixelCount, 0u);
  const auto error = [&](const char* method) {
    return metrics::compareImages(
        j.judge, displayOf(renderWith(j.scene, method, 1, 1, std::nullopt, kClaimWidth, kClaimHeight)), &j.region);
  };
  const metrics::Comparison post = error("postprocess"), hybrid = error("hybrid"), rays = error("hybrid-rays"),
                           sharp = error("sharp");
  ASSERT_TRUE(post.region && hybrid.region && rays.region && sharp.region);
  EXPECT_GE(hybrid.region->psnr, post.region->psnr);
  EXPECT_GE(hybrid.frame.psnr, post.frame.psnr);
  EXPECT_GE(rays.region->psnr, post.region->psnr);
  EXPECT_GE(rays.frame.psnr, post.frame.psnr);
  std::cout << "[ riding ] blur region (" << j.region.pixelCount << " px) PSNR sharp " << sharp.region->psnr
            << " dB, post-process " << post.region->psnr << " dB, hybrid " << hybrid.region->psnr
            << " dB, hybrid-rays " << rays.region->psnr << " dB; frame " << post.frame.psnr << " / "
            << hybrid.frame.psnr << " / " << rays.frame.psnr << " dB\n";
}

TEST(ReferenceSettingsTest, AbsurdSettingsAreRejected) {
  RenderSettings settings;
  settings.method = Method::Reference;
  settings.reference.samplesPerPixel = 0;
  EXPECT_THROW(validateRenderSettings(settings), Error);
  settings.reference.samplesPerPixel = 1u << 30;
  EXPECT_THROW(validateRenderSettings(settings), Error);
  settings.reference.samplesPerPixel = 4;
  settings.reference.checkpoint = "/nonexistent-dir/x.bin";
  EXPECT_THROW(validateRenderSettings(settings), Error);
}

}  // namespace
}  // namespace hmb::test
