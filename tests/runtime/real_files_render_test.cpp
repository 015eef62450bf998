// Every real glTF 2.0 file of the assimp test models (Debian assimp-testmodels) either renders
// a finite sharp frame that shows its geometry and a finite hybrid frame (every pass of the
// project on it: raster, BVH, mask, reveal, gathers), or is refused with a one-line hmb::Error
// while loading. Skipped when the package is not installed.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "scenes/assimp_test_models.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> realGltfFiles() {
  std::vector<fs::path> files;
  const fs::path root = scene::assimpGltfModels();
  if (root.empty()) return files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

using RealFilesRenderTest = VulkanTest;

TEST_F(RealFilesRenderTest, EveryLoadableFileRendersAFiniteFrameThatShowsItsGeometry) {
  const std::vector<fs::path> files = realGltfFiles();
  if (files.empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
  Renderer renderer(context());
  RenderSettings settings;
  settings.width = 48;
  settings.height = 32;
  size_t rendered = 0;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    scene::Scene scene;
    try {
      scene = scene::loadScene(file.string());
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      continue;
    }
    const RenderResult result = renderer.render(scene, settings);
    for (float v : result.image.find("")->values) ASSERT_TRUE(std::isfinite(v));
    const auto& ids = result.image.find("objectId")->ids;
    const auto covered = std::count_if(ids.begin(), ids.end(), [](uint32_t id) { return id != 0; });
    if (scene.triangleCount() > 0) {
      EXPECT_GT(covered, 0) << "the default or given camera should see the scene";
    }
    RenderSettings hybrid = settings;
    hybrid.method = Method::Hybrid;
    const RenderResult blurred = renderer.render(scene, hybrid);
    for (float v : blurred.image.find("")->values) ASSERT_TRUE(std::isfinite(v)) << "hybrid";
    ++rendered;
  }
  EXPECT_GT(rendered, files.size() / 2);
}

}  // namespace
}  // namespace hmb::test
