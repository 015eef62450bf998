// Golden hashes of every method's output (beauty, AOV layers and display) on the three reference
// scenes at 160x90. They guard refactors: a change that should not touch the images must leave
// every hash as it is. A change that means to alter an image updates the table, with the reason
// in its commit message (HMB_PRINT_GOLDEN=1 prints the table this build renders).
//
// Float results depend on the driver's code generation (Mesa version, vector width, fused
// multiply-add on the CPU), so the table is kept per configuration. The display images themselves are kept too (tests/runtime/golden/, 160x90
// PNGs, HMB_WRITE_GOLDEN=1 rewrites them), so that a configuration without a table, a GPU
// among them, is still checked: each display image within 60 dB PSNR of the stored one. Vulkan's
// precision rules let a driver round division, square root and transcendental functions
// otherwise, and fuse or split multiply-adds; such rounding moves a display value by one step
// in 255 where it lies near a step, which costs far less than 60 dB (every value one step off
// is 48 dB), while a changed pixel, a mask that flips or a hit on another surface costs more.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "runtime/io/image_files.h"
#include "tests/support/display_psnr.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using GoldenImagesTest = VulkanTest;

struct GoldenCase {
  const char* name;
  const char* method;
  void (*configure)(RenderSettings&);
};

const std::vector<GoldenCase>& goldenCases() {
  static const std::vector<GoldenCase> cases = {
      {"sharp", "sharp", [](RenderSettings&) {}},
      {"postprocess", "postprocess", [](RenderSettings&) {}},
      {"postprocess-centered", "postprocess", [](RenderSettings& s) { s.postprocess.range = passes::GatherRange::Centered; }},
      {"postprocess-jimenez", "postprocess", [](RenderSettings& s) { s.postprocess.filter = passes::PostProcessFilter::Jimenez; }},
      // The paper's hybrid: ray mask, reveal and composite.
      {"hybrid", "hybrid", [](RenderSettings&) {}},
      {"hybrid-rays", "hybrid-rays", [](RenderSettings&) {}},
      // Under a ray budget: the paper's chain, and the budget's best pixels traced over it.
      {"hybrid-rays-budget", "hybrid-rays", [](RenderSettings& s) { s.hybrid.rayBudget = 1000; }},
      {"hybrid-luminance-weights", "hybrid",
       [](RenderSettings& s) {
         s.hybrid.stop = passes::RevealStop::Luminance;
         s.hybrid.composite = passes::HybridComposite::Weights;
       }},
      {"reference", "reference", [](RenderSettings& s) { s.reference.samplesPerPixel = 8; }},
  };
  return cases;
}

// FNV-1a over the bytes of every layer (name, channels, values) and of the display image.
class Fnv1a {
 public:
  void add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s) { add(s.data(), s.size() + 1); }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;
};

uint64_t imageHash(const RenderResult& result) {
  Fnv1a hash;
  for (const io::ImageLayer& layer : result.image.layers) {
    hash.add(layer.name);
    for (const std::string& channel : layer.channels) hash.add(channel);
    hash.add(layer.values.data(), layer.values.size() * sizeof(float));
    hash.add(layer.ids.data(), layer.ids.size() * sizeof(uint32_t));
  }
  hash.add(result.display.pixels.data(), result.display.pixels.size());
  if (result.hybrid) {
    const uint64_t counts[] = {result.hybrid->edgeCandidates, result.hybrid->maskPixels, result.hybrid->revealedPixels,
                               result.hybrid->revealRays};
    hash.add(counts, sizeof(counts));
  }
  return hash.value();
}

// What the float results depend on. On lavapipe: its LLVM version and whether the CPU fuses
// multiply-adds (the same hashes were measured on Mesa 22.3 and 25, at 128- and 256-bit vectors,
// under either device profile); elsewhere the device and its driver.
std::string configurationKey(const vk::Context& context) {
  const vk::DeviceInfo& info = context.info();
  if (info.name.rfind("llvmpipe", 0) != 0) return info.name + " | " + info.driverInfo;
  std::string key = info.name.substr(0, info.name.find(", "));  // "llvmpipe (LLVM 15.0.6"
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  bool fma = false;
  while (std::getline(cpuinfo, line))
    if (line.rfind("flags", 0) == 0) {
      fma = (line + " ").find(" fma ") != std::string::npos;
      break;
    }
  return key + ") | " + (fma ? "fma" : "no fma");
}

using GoldenTable = std::map<std::string, uint64_t>;  // "scene/case" -> hash

// Recorded with HMB_PRINT_GOLDEN=1 on each configuration; see the header for when to update.
const std::map<std::string, GoldenTable>& goldenTables() {
  static const std::map<std::string, GoldenTable> tables = {
      {"llvmpipe (LLVM 15.0.6) | fma",
       {
           {"bistro/hybrid", 0x56ea15c148342036ull},
           {"bistro/hybrid-luminance-weights", 0x2ae2623a2596c5e6ull},
           {"bistro/hybrid-rays", 0x129d44157592ca8eull},
           {"bistro/hybrid-rays-budget", 0x5f207b0d94ffaa1cull},
           {"bistro/postprocess", 0xd04fbd278c9e9ab2ull},
           {"bistro/postprocess-centered", 0x274d4cc21df83884ull},
           {"bistro/postprocess-jimenez", 0x5378f756f0611aa9ull},
           {"bistro/reference", 0x0ac08f71faab1608ull},
           {"bistro/sharp", 0x7fb093e0005e3fd5ull},
           {"living-room/hybrid", 0x4b4c4330f692e7d6ull},
           {"living-room/hybrid-luminance-weights", 0xdae2fa997c46ff2dull},
           {"living-room/hybrid-rays", 0x577ed8e0e3078300ull},
           {"living-room/hybrid-rays-budget", 0x280d523ce513591eull},
           {"living-room/postprocess", 0x4b8fa161735d0f7eull},
           {"living-room/postprocess-centered", 0x411d2be17e8bf61eull},
           {"living-room/postprocess-jimenez", 0x7c32d30064d12f74ull},
           {"living-room/reference", 0x416649e371ea077dull},
           {"living-room/sharp", 0xcfe034f2329dce83ull},
           {"temple/hybrid", 0x9cd7a69fe064dc00ull},
           {"temple/hybrid-luminance-weights", 0xd061034749b6be9full},
           {"temple/hybrid-rays", 0x48b3bd4d65f1715dull},
           {"temple/hybrid-rays-budget", 0xfe3f05386a51d26aull},
           {"temple/postprocess", 0x4d8aa406cb8d38a2ull},
           {"temple/postprocess-centered", 0x477ddf9745fab217ull},
           {"temple/postprocess-jimenez", 0x2f93e882d9a347d2ull},
           {"temple/reference", 0x4a7a27d6e3a3a670ull},
           {"temple/sharp", 0x19be3b3bde8aee6bull},
       }},
  };
  return tables;
}

struct GoldenRender {
  GoldenTable hashes;
  std::map<std::string, io::Rgba8Image> displays;  // "scene/case" -> the display image
};

std::filesystem::path goldenImagePath(const std::string& name) {
  std::string file = name;
  std::replace(file.begin(), file.end(), '/', '-');
  return std::filesystem::path(HMB_GOLDEN_IMAGES_DIR) / (file + ".png");
}

// Every case's display image within 60 dB of the stored one (see the header for the bound).
void expectNearStoredImages(const GoldenRender& rendered) {
  for (const auto& [name, display] : rendered.displays) {
    const std::filesystem::path path = goldenImagePath(name);
    ASSERT_TRUE(std::filesystem::exists(path)) << name << ": no stored image (HMB_WRITE_GOLDEN=1 writes them)";
    const io::Rgba8Image stored = io::readPng(path);
    ASSERT_EQ(stored.width, display.width) << name;
    ASSERT_EQ(stored.height, display.height) << name;
    EXPECT_GE(displayPsnr(stored, display), 60.0) << name << " moved from " << path.filename();
  }
}

GoldenRender renderGoldenCases(vk::Context& context) {
  GoldenRender rendered;
  for (const char* sceneName : {"living-room", "temple", "bistro"}) {
    const scene::Scene scene = scene::loadScene(sceneName);
    Renderer renderer(context);
    for (const GoldenCase& c : goldenCases()) {
      RenderSettings settings;
      settings.method = parseMethod(c.method);
      settings.width = 160;
      settings.height = 90;
      c.configure(settings);
      const std::string name = std::string(sceneName) + "/" + c.name;
      RenderResult result = renderer.render(scene, settings);
      rendered.hashes[name] = imageHash(result);
      rendered.displays[name] = std::move(result.display);
    }
  }
  return rendered;
}

void expectGolden(const GoldenRender& render, const GoldenTable& golden) {
  const GoldenTable& rendered = render.hashes;
  for (const auto& [name, hash] : rendered) {
    const auto expected = golden.find(name);
    ASSERT_NE(expected, golden.end()) << name << " has no recorded hash";
    EXPECT_EQ(hash, expected->second) << name << " changed (rendered 0x" << std::hex << hash << ")";
  }
  EXPECT_EQ(rendered.size(), golden.size()) << "the table records cases this test no longer renders";
}

// Where this configuration has recorded hashes, every hash; on any configuration, every display
// image near the stored one.
TEST_F(GoldenImagesTest, EveryMethodOnEveryReferenceSceneMatchesItsRecordedImage) {
  const std::string key = configurationKey(context());
  const GoldenRender rendered = renderGoldenCases(context());
  if (std::getenv("HMB_PRINT_GOLDEN")) {
    std::printf("      {\"%s\",\n       {\n", key.c_str());
    for (const auto& [name, hash] : rendered.hashes)
      std::printf("           {\"%s\", 0x%016llxull},\n", name.c_str(), (unsigned long long)hash);
    std::printf("       }},\n");
  }
  if (std::getenv("HMB_WRITE_GOLDEN")) {
    std::filesystem::create_directories(HMB_GOLDEN_IMAGES_DIR);
    for (const auto& [name, display] : rendered.displays) io::writePng(goldenImagePath(name), display);
  }
  expectNearStoredImages(rendered);
  const auto table = goldenTables().find(key);
  if (table == goldenTables().end()) {
    std::printf("no golden hashes recorded for \"%s\": the images were checked within 60 dB\n", key.c_str());
    return;
  }
  expectGolden(rendered, table->second);
}

// A device with 8 storage buffers per stage (Mali's limit): the kernels that bind more run
// their address builds, and the images are the recorded ones.
TEST(GoldenImagesByAddressTest, ADeviceWithEightStorageBuffersRendersTheRecordedImages) {
  vk::ContextOptions options;
  options.validation = true;
  options.storageBufferLimit = 8;
  vk::Context small(options);
  if (!small.info().bufferDeviceAddress) GTEST_SKIP() << "the device has no buffer device addresses";
  const GoldenRender rendered = renderGoldenCases(small);
  expectNearStoredImages(rendered);
  const auto table = goldenTables().find(configurationKey(small));
  if (table != goldenTables().end()) expectGolden(rendered, table->second);
  EXPECT_EQ(small.validationErrors(), 0u);
}

// The kernels' address builds (their groups of buffers bound as tables of device addresses, for
// devices with few storage-buffer bindings) render the very images their plain builds do.
TEST(GoldenImagesByAddressTest, TheAddressBuildsRenderTheRecordedImages) {
  vk::ContextOptions options;
  options.validation = true;
  options.bindByAddress = true;
  vk::Context byAddress(options);
  if (!byAddress.info().bufferDeviceAddress) GTEST_SKIP() << "the device has no buffer device addresses";
  const GoldenRender rendered = renderGoldenCases(byAddress);
  expectNearStoredImages(rendered);
  const auto table = goldenTables().find(configurationKey(byAddress));
  if (table != goldenTables().end()) expectGolden(rendered, table->second);
  EXPECT_EQ(byAddress.validationErrors(), 0u);
}

}  // namespace
}  // namespace hmb::test
